#include "tools/view/web_server.h"

#include <civetweb.h>

#include <cstdio>
#include <filesystem>

namespace ahhs::view {

namespace fs = std::filesystem;

WebServer::WebServer(const Options& options, Greeting greeting, OnText on_text)
    : options_(options), greeting_(std::move(greeting)), on_text_(std::move(on_text)) {
  if (!fs::is_regular_file(fs::path(options_.web_root) / "index.html"))
    throw WebServerError("the viewer's page is not in " + options_.web_root +
                         " (index.html missing; --web-root)");
  if (!fs::is_regular_file(options_.three_js))
    throw WebServerError("three.js not found at " + options_.three_js +
                         " (tools/install-deps installs Debian's libjs-three)");
  mg_init_library(0);
  const std::string listen = options_.bind + ":" + std::to_string(options_.port);
  const char* config[] = {"listening_ports",
                          listen.c_str(),
                          "document_root",
                          options_.web_root.c_str(),
                          "enable_directory_listing",
                          "no",
                          "num_threads",
                          "8",
                          "websocket_timeout_ms",
                          "3600000",
                          "request_timeout_ms",
                          "10000",
                          nullptr};
  mg_callbacks callbacks{};
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
  mg_set_request_handler(ctx_, "/three.min.js$", &WebServer::ServeThree, this);
  mg_set_websocket_handler(ctx_, "/ws", &WebServer::OnConnect, &WebServer::OnReady,
                           &WebServer::OnData, &WebServer::OnClose, this);
  mg_server_port ports[4]{};
  const int n = mg_get_server_ports(ctx_, 4, ports);
  port_ = n > 0 ? ports[0].port : options_.port;
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

int WebServer::OnConnect(const mg_connection*, void*) { return 0; }  // accept

void WebServer::OnReady(mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  const std::vector<std::string> greeting = s->greeting_();
  std::lock_guard<std::mutex> lock(s->mutex_);
  for (const auto& m : greeting)
    mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, m.data(), m.size());
  s->pages_.insert(conn);
  if (!s->options_.announce) return;
  std::printf("ahhs-view: a page connected (%zu watching)\n", s->pages_.size());
  std::fflush(stdout);
}

int WebServer::OnData(mg_connection*, int bits, char* data, std::size_t size, void* self) {
  const int opcode = bits & 0x0f;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  auto* s = static_cast<WebServer*>(self);
  if (opcode == MG_WEBSOCKET_OPCODE_TEXT && s->on_text_ && size <= 4096)
    s->on_text_(std::string(data, size));
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

int WebServer::ServeThree(mg_connection* conn, void* self) {
  mg_send_mime_file(conn, static_cast<WebServer*>(self)->options_.three_js.c_str(),
                    "application/javascript");
  return 200;
}

}  // namespace ahhs::view
