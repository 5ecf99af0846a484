// The viewer's HTTP + WebSocket server (civetweb, Debian's libcivetweb): serves the page's own
// files by name (no document root: nothing else on disk is reachable), three.js from Debian's
// libjs-three, and pushes text messages to every page connected to /ws. Broadcast() never waits
// on the bus; a page that stops reading only delays the thread that broadcasts, and a page that
// goes away is dropped.
//
// Security (docs/viewer.md): requests whose Host is not allowed get 421 (DNS rebinding); a
// WebSocket whose Origin is another site's is refused; at most `max_pages` pages watch at once
// (more are closed with a reason), with 24 threads besides theirs for plain requests; a page says
// it is alive every few seconds and a socket that says nothing for `idle_timeout_ms` is closed; a
// message over kMaxPageMessage bytes closes its connection.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/view/access_policy.h"

struct mg_context;
struct mg_connection;

namespace ahhs::view {

class WebServerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class WebServer {
 public:
  // The largest message a page may send (its messages are a few dozen bytes).
  static constexpr std::size_t kMaxPageMessage = 1024;

  struct Options {
    std::string bind = "127.0.0.1";
    int port = 8080;                       // 0: any free port
    std::string web_root;                  // index.html, view.css, view*.js
    std::string three_js;                  // path of three.min.js
    bool announce = true;                  // print a line on stdout when a page connects or leaves
    std::vector<std::string> allow_hosts;  // names besides the loopback ones (--allow-host)
    int max_pages = 8;
    int request_timeout_ms = 5000;  // an HTTP request must arrive whole within this
    int idle_timeout_ms = 30000;    // a page that sends nothing for this long is closed
  };
  // Messages a page gets first when it connects (the current scene, recording, ...).
  using Greeting = std::function<std::vector<std::string>()>;

  // What a page sends (text messages), handed over on civetweb's thread.
  using OnText = std::function<void(const std::string&)>;

  // Throws WebServerError (port in use, bad address, missing files).
  WebServer(const Options& options, Greeting greeting, OnText on_text = {});
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  int port() const { return port_; }
  std::string url() const;
  // Sends `text` to every connected page; returns how many got it.
  int Broadcast(const std::string& text);

 private:
  static int OnRequest(mg_connection* conn);  // every request first: the Host check
  static int OnConnect(const mg_connection* conn, void* self);
  static void OnReady(mg_connection* conn, void* self);
  static int OnData(mg_connection* conn, int bits, char* data, std::size_t size, void* self);
  static void OnClose(const mg_connection* conn, void* self);
  static int ServeFile(mg_connection* conn, void* self);

  Options options_;
  Greeting greeting_;
  OnText on_text_;
  mg_context* ctx_ = nullptr;
  int port_ = 0;
  std::unique_ptr<AccessPolicy> policy_;
  std::atomic<const AccessPolicy*> active_policy_{nullptr};  // null until the port is known
  mutable std::mutex mutex_;  // guards pages_ and every write to a page
  std::set<mg_connection*> pages_;
};

}  // namespace ahhs::view
