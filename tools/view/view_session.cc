#include "tools/view/view_session.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "base/cli.h"
#include "bus/channels.h"
#include "bus/fault_bus.h"
#include "bus/log_reader.h"

namespace ahhs::view {

namespace fs = std::filesystem;

ViewSession::ViewSession(ViewOptions* o, Json hormones) : o_(*o) {
  hello_ = {{"type", "hello"}, {"hormones", std::move(hormones)}};
  if (!o->log_file.empty()) {
    std::vector<Json> recordings = LoadRecordings(o->log_file, &o->arena);
    hello_["mode"] = "log";
    hello_["title"] = fs::path(o->log_file).filename().string();
    hello_["arena"] = o->arena;
    std::size_t frames_total = 0;
    for (auto& r : recordings) {
      frames_total += r["frames"].size();
      fixed_.push_back(r.dump());
    }
    what_ = o->log_file + " (arena " + o->arena + ", " + std::to_string(recordings.size()) +
            " episode(s), " + std::to_string(frames_total) + " states)";
  } else if (!o->run_dir.empty()) {
    scratch_ = std::make_unique<ahhs::base::TempDir>("ahhs-view-");
    follower_ = std::make_unique<RunFollower>(o->run_dir, scratch_->path());
    hello_["waiting"] = follower_->waiting_for();
    hello_["mode"] = "run";
    hello_["title"] = o->run_dir;
    what_ = "run " + o->run_dir;
  } else {
    if (o->arena.empty()) o->arena = ahhs::bus::kDefaultArena;
    bus_ = ahhs::bus::OpenBusWithFaultInjection(o->lcm_url);
    bridge_ = std::make_unique<LiveBridge>(*bus_, o->arena);
    hello_["mode"] = "live";
    hello_["title"] = "arena " + o->arena;
    hello_["arena"] = o->arena;
    what_ = "arena " + o->arena + " on " + o->lcm_url;
  }
}

std::vector<std::string> ViewSession::Greeting() {
  std::vector<std::string> g{hello_.dump()};
  std::lock_guard<std::mutex> lock(greeting_mutex_);
  g.insert(g.end(), fixed_.begin(), fixed_.end());
  if (bridge_) {
    auto s = bridge_->Snapshot();
    g.insert(g.end(), s.begin(), s.end());
  }
  return g;
}

void ViewSession::OnPageMessage(const std::string& text) {
  const auto m = nlohmann::json::parse(text, nullptr, false);
  if (bridge_ && m.is_object() && m.value("type", "") == "select" && m.contains("module") &&
      m["module"].is_number_integer())
    bridge_->Want(m["module"].get<int>());
}

int ViewSession::Serve(WebServer& server, const std::atomic<bool>& stop) {
  if (bridge_) {
    // At --rate: take every message that arrived (the bus queues them), send what changed. The
    // viewer wakes at its own pace, not once per message of the arena it watches.
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / o_.rate));
    auto next = std::chrono::steady_clock::now();
    while (!stop) {
      next = std::max(next + period, std::chrono::steady_clock::now() - period);  // no bursts
      std::this_thread::sleep_until(next);
      while (bus_->Handle(std::chrono::microseconds(0)) > 0) {
      }
      bridge_->Maintain();
      for (const auto& m : bridge_->Drain()) server.Broadcast(m);
    }
    std::printf("ahhs-view: %llu states seen, %llu messages that did not decode\n",
                static_cast<unsigned long long>(bridge_->states_seen()),
                static_cast<unsigned long long>(bridge_->undecodable()));
  } else if (follower_) {
    while (!stop) {
      try {
        if (auto r = follower_->Poll()) {
          const std::string text = r->dump();
          {
            std::lock_guard<std::mutex> lock(greeting_mutex_);
            fixed_ = {text};
          }
          server.Broadcast(text);
          std::printf("ahhs-view: showing %s\n", (*r)["title"].get<std::string>().c_str());
          std::fflush(stdout);
        }
      } catch (const std::exception& e) {
        std::cerr << "ahhs-view: " << e.what() << '\n';
        return ahhs::base::kExitFailure;
      }
      for (int i = 0; i < static_cast<int>(o_.poll * 10) && !stop; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  } else {
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

}  // namespace ahhs::view
