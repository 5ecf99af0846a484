#!/usr/bin/env python3
"""Plain-socket probes of ahhs-view (tests/tools/view_security_test.sh): what a hostile local
process or a page of another site can send, without a browser. Exit 0 when the viewer answered
as expected, 1 with a message otherwise.

  view_probe.py PORT get PATH [--host H] --expect CODE
  view_probe.py PORT upgrade [--origin O] [--host H] --expect 101|421|refused
  view_probe.py PORT idle-then-get --idle N --expect CODE
  view_probe.py PORT oversize --size BYTES
  view_probe.py PORT cap --pages N
"""
import argparse
import base64
import os
import socket
import struct
import sys
import time

TIMEOUT = 10


def connect(port):
    s = socket.create_connection(("127.0.0.1", port), timeout=TIMEOUT)
    return s


def read_head(s):
    """The status code of an HTTP response (None: closed without one) and bytes after it."""
    data = b""
    while b"\r\n\r\n" not in data:
        try:
            chunk = s.recv(4096)
        except (ConnectionResetError, socket.timeout):
            return None, b""
        if not chunk:
            return None, b""
        data += chunk
    head, rest = data.split(b"\r\n\r\n", 1)
    return int(head.split(b" ")[1]), rest


def get(port, path, host=None, timeout=TIMEOUT):
    s = connect(port)
    s.settimeout(timeout)
    host = host or "127.0.0.1:%d" % port
    s.sendall(("GET %s HTTP/1.1\r\nHost: %s\r\nConnection: close\r\n\r\n" % (path, host)).encode())
    code, _ = read_head(s)
    s.close()
    return code


def upgrade(port, origin=None, host=None):
    """A WebSocket handshake; returns (status or None, socket, bytes already read)."""
    s = connect(port)
    host = host or "127.0.0.1:%d" % port
    key = base64.b64encode(os.urandom(16)).decode()
    req = ("GET /ws HTTP/1.1\r\nHost: %s\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
           "Sec-WebSocket-Key: %s\r\nSec-WebSocket-Version: 13\r\n" % (host, key))
    if origin is not None:
        req += "Origin: %s\r\n" % origin
    s.sendall((req + "\r\n").encode())
    code, rest = read_head(s)
    return code, s, rest


def frame(opcode, payload):
    """A masked client frame (RFC 6455)."""
    mask = os.urandom(4)
    n = len(payload)
    if n < 126:
        head = struct.pack("!BB", 0x80 | opcode, 0x80 | n)
    elif n < 65536:
        head = struct.pack("!BBH", 0x80 | opcode, 0x80 | 126, n)
    else:
        head = struct.pack("!BBQ", 0x80 | opcode, 0x80 | 127, n)
    return head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))


class Frames:
    """Server frames from a socket (unmasked)."""

    def __init__(self, s, rest=b""):
        self.s, self.buf = s, rest

    def _need(self, n):
        while len(self.buf) < n:
            chunk = self.s.recv(65536)
            if not chunk:
                raise EOFError("closed")
            self.buf += chunk

    def next(self):
        self._need(2)
        b0, b1 = self.buf[0], self.buf[1]
        n, at = b1 & 0x7F, 2
        if n == 126:
            self._need(4)
            n, at = struct.unpack("!H", self.buf[2:4])[0], 4
        elif n == 127:
            self._need(10)
            n, at = struct.unpack("!Q", self.buf[2:10])[0], 10
        self._need(at + n)
        payload = self.buf[at:at + n]
        self.buf = self.buf[at + n:]
        return b0 & 0x0F, payload

    def until_close(self):
        """Reads frames until a close frame: (code, reason), or (None, '') if the socket ends."""
        try:
            while True:
                op, payload = self.next()
                if op == 8:
                    code = struct.unpack("!H", payload[:2])[0] if len(payload) >= 2 else None
                    return code, payload[2:].decode(errors="replace")
        except (EOFError, ConnectionResetError, socket.timeout):
            return None, ""


def alive(s, rest=b""):
    """Whether a page's connection still answers: a ping gets a pong."""
    s.sendall(frame(9, b"are-you-there"))
    f = Frames(s, rest)
    try:
        while True:
            op, payload = f.next()
            if op == 10 and payload == b"are-you-there":
                return True
            if op == 8:
                return False
    except (EOFError, ConnectionResetError, socket.timeout):
        return False


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("port", type=int)
    ap.add_argument("what")
    ap.add_argument("path", nargs="?")
    ap.add_argument("--host")
    ap.add_argument("--origin")
    ap.add_argument("--expect")
    ap.add_argument("--idle", type=int, default=0)
    ap.add_argument("--size", type=int, default=0)
    ap.add_argument("--pages", type=int, default=0)
    a = ap.parse_args()
    if a.what == "get":
        code = get(a.port, a.path, a.host)
        if str(code) != a.expect:
            sys.exit("GET %s (Host %s): %s, expected %s" % (a.path, a.host, code, a.expect))
    elif a.what == "upgrade":
        code, s, _ = upgrade(a.port, a.origin, a.host)
        s.close()
        got = "refused" if code is None or code in (400, 403) else str(code)
        if got != a.expect:
            sys.exit("upgrade (Origin %s, Host %s): %s, expected %s" % (a.origin, a.host, code,
                                                                       a.expect))
    elif a.what == "idle-then-get":
        idle = [connect(a.port) for _ in range(a.idle)]
        idle += [connect(a.port) for _ in range(a.idle)]  # and as many with half a request
        for s in idle[a.idle:]:
            s.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        time.sleep(0.5)
        # Within 3 s, before the viewer's 5-s request timeout would have freed a held thread.
        code = get(a.port, "/", timeout=3)
        for s in idle:
            s.close()
        if str(code) != a.expect:
            sys.exit("with %d idle sockets GET / gave %s" % (2 * a.idle, code))
        print("GET / with %d idle sockets: %s" % (2 * a.idle, code))
    elif a.what == "oversize":
        code1, bystander, rest1 = upgrade(a.port)
        code2, attacker, rest2 = upgrade(a.port)
        if code1 != 101 or code2 != 101:
            sys.exit("pages did not connect: %s %s" % (code1, code2))
        attacker.sendall(frame(1, b"x" * a.size))
        close, reason = Frames(attacker, rest2).until_close()
        if close != 1009:
            sys.exit("an oversized message: close %s %r, expected 1009" % (close, reason))
        if not alive(bystander, rest1):
            sys.exit("the other page was closed too")
        print("oversized message: closed with 1009 (%s); the other page still answers" % reason)
    elif a.what == "cap":
        pages = []
        for _ in range(a.pages):
            code, s, rest = upgrade(a.port, "http://127.0.0.1:%d" % a.port)
            if code != 101:
                sys.exit("page %d of %d refused: %s" % (len(pages) + 1, a.pages, code))
            pages.append((s, rest))
        time.sleep(0.3)
        code, extra, rest = upgrade(a.port, "http://127.0.0.1:%d" % a.port)
        close, reason = Frames(extra, rest).until_close() if code == 101 else (None, "")
        if close != 1013 or "--max-pages" not in reason:
            sys.exit("page %d: close %s %r, expected 1013 naming --max-pages" % (a.pages + 1,
                                                                                 close, reason))
        if not alive(*pages[0]):
            sys.exit("a page within the cap was closed")
        print("page %d refused: %s" % (a.pages + 1, reason))
    else:
        sys.exit("unknown probe " + a.what)


if __name__ == "__main__":
    main()
