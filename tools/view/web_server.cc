#include "tools/view/web_server.h"

#include <civetweb.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

namespace ahhs::view {

namespace fs = std::filesystem;

namespace {

// The files the viewer serves, by URI: nothing else is reachable.
struct Served {
  const char* uri;
  const char* file;  // in web_root; null: three.js
  const char* mime;
};
constexpr Served kServed[] = {
    {"/", "index.html", "text/html; charset=utf-8"},
    {"/index.html", "index.html", "text/html; charset=utf-8"},
    {"/view_scene.js", "view_scene.js", "application/javascript"},
    {"/view_frames.js", "view_frames.js", "application/javascript"},
    {"/view_panel.js", "view_panel.js", "application/javascript"},
    {"/view.js", "view.js", "application/javascript"},
    {"/view.css", "view.css", "text/css"},
    {"/three.min.js", nullptr, "application/javascript"},
};

constexpr char kHeaders[] =
    "X-Content-Type-Options: nosniff\r\nCache-Control: no-store\r\n"
    "Referrer-Policy: no-referrer\r\n";

// A close frame: 2-byte status code, then the reason (RFC 6455, 5.5.1).
void Close(mg_connection* conn, int code, const std::string& reason) {
  std::string payload;
  payload += static_cast<char>((code >> 8) & 0xff);
  payload += static_cast<char>(code & 0xff);
  payload += reason.substr(0, 120);
  mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE, payload.data(), payload.size());
}

}  // namespace

WebServer::WebServer(const Options& options, Greeting greeting, OnText on_text)
    : options_(options), greeting_(std::move(greeting)), on_text_(std::move(on_text)) {
  for (const Served& s : kServed)
    if (s.file && !fs::is_regular_file(fs::path(options_.web_root) / s.file))
      throw WebServerError(std::string("the viewer's page is not in ") + options_.web_root + " (" +
                           s.file + " missing; --web-root)");
  if (!fs::is_regular_file(options_.three_js))
    throw WebServerError("three.js not found at " + options_.three_js +
                         " (tools/install-deps installs Debian's libjs-three)");
  if (options_.max_pages < 1) throw WebServerError("at least one page must be allowed");
  mg_init_library(0);
  const std::string listen = options_.bind + ":" + std::to_string(options_.port);
  // A page holds one thread while it watches; 24 more answer plain requests, so a few idle
  // sockets (each held for request_timeout_ms at most) cannot keep the page from loading.
  const std::string threads = std::to_string(options_.max_pages + 24);
  const std::string request_timeout = std::to_string(options_.request_timeout_ms);
  const std::string idle_timeout = std::to_string(options_.idle_timeout_ms);
  // No document_root: civetweb serves no files, runs no CGI or SSI and lists no folders; the
  // handlers below answer every URI.
  const char* config[] = {"listening_ports",
                          listen.c_str(),
                          "num_threads",
                          threads.c_str(),
                          "request_timeout_ms",
                          request_timeout.c_str(),
                          "websocket_timeout_ms",
                          idle_timeout.c_str(),
                          "enable_websocket_ping_pong",
                          "no",
                          "enable_keep_alive",
                          "no",
                          "max_request_size",
                          "8192",
                          nullptr};
  mg_callbacks callbacks{};
  callbacks.begin_request = &WebServer::OnRequest;
  callbacks.log_message = [](const mg_connection*, const char*) { return 1; };  // no stderr noise
  mg_init_data init{};
  init.callbacks = &callbacks;
  init.user_data = this;
  init.configuration_options = config;
  char text[256] = "";
  unsigned code = 0;
  mg_error_data error{&code, text, sizeof text};
  ctx_ = mg_start2(&init, &error);
  if (ctx_ == nullptr) {
    mg_exit_library();
    throw WebServerError("cannot serve on " + listen +
                         " (a port in use, or an address not of this machine: --port, --bind): " +
                         (text[0] ? std::string(text) : std::string("civetweb failed to start")));
  }
  mg_set_websocket_handler(ctx_, "/ws$", &WebServer::OnConnect, &WebServer::OnReady,
                           &WebServer::OnData, &WebServer::OnClose, this);
  mg_set_request_handler(ctx_, "/", &WebServer::ServeFile, this);
  mg_server_port ports[4]{};
  const int n = mg_get_server_ports(ctx_, 4, ports);
  port_ = n > 0 ? ports[0].port : options_.port;
  policy_ = std::make_unique<AccessPolicy>(options_.bind, port_, options_.allow_hosts);
  active_policy_ = policy_.get();
}

WebServer::~WebServer() {
  mg_stop(ctx_);  // closes every page (OnClose) and joins civetweb's threads
  mg_exit_library();
}

std::string WebServer::url() const {
  const std::string host = options_.bind == "0.0.0.0" ? "127.0.0.1" : options_.bind;
  return "http://" + host + ":" + std::to_string(port_) + "/";
}

int WebServer::Broadcast(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  int sent = 0;
  for (mg_connection* c : pages_)
    if (mg_websocket_write(c, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size()) > 0) ++sent;
  return sent;
}

int WebServer::OnRequest(mg_connection* conn) {
  auto* s = static_cast<WebServer*>(mg_get_request_info(conn)->user_data);
  const AccessPolicy* policy = s->active_policy_.load();
  if (policy == nullptr) {
    mg_send_http_error(conn, 503, "ahhs-view is starting");
    return 503;
  }
  if (!policy->HostAllowed(mg_get_header(conn, "Host"))) {
    // Written whole here: civetweb's mg_send_http_error leaves out the status line and headers
    // when the request asks for a WebSocket.
    const std::string body = "ahhs-view answers only to " + policy->Describe() +
                             " (ahhs-view --allow-host NAME adds a name)\n";
    mg_printf(conn,
              "HTTP/1.1 421 Misdirected Request\r\nContent-Type: text/plain; charset=utf-8\r\n"
              "Content-Length: %zu\r\nConnection: close\r\n%s\r\n%s",
              body.size(), kHeaders, body.c_str());
    return 421;
  }
  return 0;  // on to the handlers
}

int WebServer::OnConnect(const mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  const AccessPolicy* policy = s->active_policy_.load();
  if (policy == nullptr || !policy->HostAllowed(mg_get_header(conn, "Host")) ||
      !policy->OriginAllowed(mg_get_header(conn, "Origin")))
    return 1;  // refused: no upgrade, the connection is closed
  return 0;
}

void WebServer::OnReady(mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  {
    std::lock_guard<std::mutex> lock(s->mutex_);
    if (static_cast<int>(s->pages_.size()) >= s->options_.max_pages) {
      Close(conn, 1013,
            "ahhs-view: " + std::to_string(s->options_.max_pages) +
                " pages are watching already (--max-pages)");
      return;
    }
  }
  const std::vector<std::string> greeting = s->greeting_();
  std::lock_guard<std::mutex> lock(s->mutex_);
  for (const auto& m : greeting)
    mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, m.data(), m.size());
  s->pages_.insert(conn);
  if (!s->options_.announce) return;
  std::printf("ahhs-view: a page connected (%zu watching)\n", s->pages_.size());
  std::fflush(stdout);
}

int WebServer::OnData(mg_connection* conn, int bits, char* data, std::size_t size, void* self) {
  const int opcode = bits & 0x0f;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  auto* s = static_cast<WebServer*>(self);
  {
    std::lock_guard<std::mutex> lock(s->mutex_);
    if (s->pages_.count(conn) == 0) return 0;  // refused (too many pages): say nothing more
    if (size > kMaxPageMessage) {
      Close(conn, 1009, "ahhs-view: a page's message is at most 1024 bytes");
      return 0;
    }
  }
  if (opcode == MG_WEBSOCKET_OPCODE_PING) {  // civetweb 1.15 leaves the pong to us (RFC 6455)
    std::lock_guard<std::mutex> lock(s->mutex_);
    mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_PONG, data, size);
  }
  if (opcode == MG_WEBSOCKET_OPCODE_TEXT && s->on_text_) s->on_text_(std::string(data, size));
  return 1;
}

void WebServer::OnClose(const mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  std::lock_guard<std::mutex> lock(s->mutex_);
  if (s->pages_.erase(const_cast<mg_connection*>(conn)) == 0) return;  // not a page (HTTP)
  if (!s->options_.announce) return;
  std::printf("ahhs-view: a page left (%zu watching)\n", s->pages_.size());
  std::fflush(stdout);
}

int WebServer::ServeFile(mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  const mg_request_info* info = mg_get_request_info(conn);
  const char* uri = info->local_uri_raw ? info->local_uri_raw : "";
  for (const Served& f : kServed) {
    if (std::strcmp(uri, f.uri) != 0) continue;
    if (std::strcmp(info->request_method, "GET") != 0 &&
        std::strcmp(info->request_method, "HEAD") != 0) {
      mg_send_http_error(conn, 405, "ahhs-view serves GET and HEAD only");
      return 405;
    }
    const std::string path =
        f.file ? (fs::path(s->options_.web_root) / f.file).string() : s->options_.three_js;
    mg_send_mime_file2(conn, path.c_str(), f.mime, kHeaders);
    return 200;
  }
  mg_send_http_error(conn, 404, "not found");
  return 404;
}

}  // namespace ahhs::view
