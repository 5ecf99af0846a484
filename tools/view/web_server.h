// The viewer's HTTP + WebSocket server (civetweb, Debian's libcivetweb): serves the page from
// `web_root`, three.js from Debian's libjs-three, and pushes text messages to every page
// connected to /ws. Broadcast() never waits on the bus; a page that stops reading only delays
// the thread that broadcasts, and a page that goes away is dropped.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

struct mg_context;
struct mg_connection;

namespace ahhs::view {

class WebServerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class WebServer {
 public:
  struct Options {
    std::string bind = "127.0.0.1";
    int port = 8080;  // 0: any free port
    std::string web_root;
    std::string three_js;  // path of three.min.js
    bool announce = true;  // print a line on stdout when a page connects or leaves
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
  static int OnConnect(const mg_connection* conn, void* self);
  static void OnReady(mg_connection* conn, void* self);
  static int OnData(mg_connection* conn, int bits, char* data, std::size_t size, void* self);
  static void OnClose(const mg_connection* conn, void* self);
  static int ServeThree(mg_connection* conn, void* self);

  Options options_;
  Greeting greeting_;
  OnText on_text_;
  mg_context* ctx_ = nullptr;
  int port_ = 0;
  mutable std::mutex mutex_;  // guards pages_ and every write to a page
  std::set<mg_connection*> pages_;
};

}  // namespace ahhs::view
