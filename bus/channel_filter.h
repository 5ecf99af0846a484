// Kernel-side channel filter for LCM's UDP multicast: a classic BPF socket filter that lets a
// receive socket take only the datagrams whose LCM channel one of its subscriptions can match.
// Why: on one multicast group every process receives every datagram; in a 5-module lockstep
// arena that is 8 processes x 18 datagrams per tick, each waking LCM's receive thread only for
// LCM to drop most of them. With the filter the kernel drops them before anyone wakes.
// Pure code (no LCM): LcmBus attaches the program to its receive socket.
//
// The filter is conservative: it may let through more than the subscriptions match (LCM's own
// dispatch still decides), never less. LCM datagrams (docs/protocol.md, LCM's UDP format): a
// short message is magic "LC02", sequence number (4 bytes), the channel name, NUL, the payload;
// fragments ("LC03") and anything else pass unfiltered, except datagrams shorter than 4 bytes
// (no LCM datagram is), which are dropped.
#pragma once

#include <linux/filter.h>

#include <string>
#include <vector>

namespace ahhs::bus {

// The bytes every channel matched by the LCM subscription regex `regex` starts with. For a
// literal channel name (letters, digits, '/', '_', '-', ':') it is the name followed by NUL, so
// only that exact channel matches; for a regular expression, the literal text before its first
// special character (dropping a character a quantifier makes optional). Empty when nothing can
// be said (e.g. ".*", or an alternation): such a subscription needs every datagram.
std::string ChannelPrefix(const std::string& regex);

// A socket filter that accepts a datagram when its channel starts with one of `prefixes`
// (ChannelPrefix values), and every datagram that is not an LCM short message. The datagram's
// payload starts `payload_offset` bytes into what the filter sees: 8 for a UDP socket (the UDP
// header comes first), 0 for a datagram Unix socket (tests). Returns an empty program when no
// filtering is possible (an empty prefix among them, or too long a program): accept everything.
// With no prefixes at all, LCM short messages are all dropped.
std::vector<sock_filter> BuildChannelFilter(const std::vector<std::string>& prefixes,
                                            unsigned payload_offset);

}  // namespace ahhs::bus
