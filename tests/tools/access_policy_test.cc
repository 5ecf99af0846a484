#include "tools/view/access_policy.h"

#include <catch2/catch.hpp>

using ahhs::view::AccessPolicy;

TEST_CASE("the viewer answers loopback hosts on its port, its bind address and named hosts",
          "[view][security]") {
  const AccessPolicy p("127.0.0.1", 8080, {"Lab-PC", "10.0.0.5:9000", "[fe80::1]"});
  for (const char* host : {"127.0.0.1:8080", "localhost:8080", "LOCALHOST:8080", "[::1]:8080",
                           "lab-pc:8080", "10.0.0.5:9000", "[fe80::1]:8080"})
    CHECK(p.HostAllowed(host));
  for (const char* host : {"evil.example", "evil.example:8080", "127.0.0.1", "127.0.0.1:8081",
                           "localhost", "lab-pc", "10.0.0.5:8080", "127.0.0.1:8080.evil", ""})
    CHECK_FALSE(p.HostAllowed(host));
  CHECK_FALSE(p.HostAllowed(nullptr));
  CHECK(p.Describe().find("localhost:8080") != std::string::npos);

  CHECK(AccessPolicy("192.168.1.2", 80).HostAllowed("192.168.1.2"));  // browsers omit :80
  CHECK(AccessPolicy("192.168.1.2", 80).HostAllowed("192.168.1.2:80"));
  CHECK_FALSE(AccessPolicy("0.0.0.0", 8080).HostAllowed("0.0.0.0:8080"));  // a wildcard
  CHECK(AccessPolicy("::1", 8080).HostAllowed("[::1]:8080"));
}

TEST_CASE("a WebSocket's Origin must be absent or the viewer's own", "[view][security]") {
  const AccessPolicy p("127.0.0.1", 8080);
  CHECK(p.OriginAllowed(nullptr));
  CHECK(p.OriginAllowed("http://127.0.0.1:8080"));
  CHECK(p.OriginAllowed("http://localhost:8080"));
  for (const char* origin : {"null", "http://evil.example", "https://127.0.0.1:8080",
                             "http://127.0.0.1:8081", "http://127.0.0.1", "file://", ""})
    CHECK_FALSE(p.OriginAllowed(origin));
}

TEST_CASE("the viewer's --allow-host takes names and addresses only", "[view][security]") {
  CHECK(AccessPolicy::CheckName("lab-pc.local") == "");
  CHECK(AccessPolicy::CheckName("10.0.0.5:9000") == "");
  CHECK(AccessPolicy::CheckName("[fe80::1]") == "");
  CHECK_FALSE(AccessPolicy::CheckName("").empty());
  CHECK_FALSE(AccessPolicy::CheckName("fe80::1").empty());
  CHECK_FALSE(AccessPolicy::CheckName("a b").empty());
  CHECK_FALSE(AccessPolicy::CheckName("http://x").empty());
}
