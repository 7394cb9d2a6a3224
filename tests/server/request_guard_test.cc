// SPDX-License-Identifier: MIT
// Who may drive the station (server/src/request_guard.h, docs/operator-station.md): a page of
// another site in the operator's browser, a name rebound to the station, a body of any transfer
// encoding over the limit, and connections that sit idle or trickle; through httplib's client and
// raw sockets against a server on an ephemeral port.
#include "request_guard.h"

#include <atomic>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "station_fixture.h"
#include "worker_pool.h"
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <zlib.h>

namespace sewerplan::server {
namespace {

using ::testing::HasSubstr;

// A TCP connection of our own to the station: requests written byte for byte.
class RawConnection {
 public:
  explicit RawConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = fd_ >= 0 &&
                 ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return connected_; }
  // Whether all of `bytes` went out (false once the station has closed the connection).
  bool send(std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
      if (n <= 0) return false;
      bytes.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
  }
  // What the station answers within `timeout_s`, until it closes the connection.
  std::string receive(int timeout_s) {
    std::string answer;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
    char buffer[4096];
    while (std::chrono::steady_clock::now() < deadline) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      answer.append(buffer, static_cast<std::size_t>(n));
    }
    return answer;
  }

 private:
  int fd_;
  bool connected_ = false;
};

// The JSON body of a raw answer.
json body_of(const std::string& answer) {
  const std::size_t start = answer.find("\r\n\r\n");
  return json::parse(start == std::string::npos ? "" : answer.substr(start + 4), nullptr, false);
}

class RequestGuardTest : public StationFixture {
 protected:
  std::string here() const { return "127.0.0.1:" + std::to_string(port_); }
  std::size_t map_count() { return get("/api/maps").second["maps"].size(); }
};

TEST(HostName, IsTheHostHeadersNameWithoutItsPortLowerCased) {
  EXPECT_EQ(host_name("127.0.0.1:8080"), "127.0.0.1");
  EXPECT_EQ(host_name("[::1]:8080"), "::1");
  EXPECT_EQ(host_name("[::1]"), "::1");
  EXPECT_EQ(host_name("Station.LAN"), "station.lan");
  EXPECT_EQ(host_name("localhost:80"), "localhost");
  EXPECT_EQ(host_name("evil.example:80:80"), "");
  EXPECT_EQ(host_name("evil.example:"), "");
  EXPECT_EQ(host_name("[::1"), "");
  EXPECT_EQ(host_name("[::1]x"), "");
}

// DNS rebinding: a page of evil.example whose name is made to resolve to 127.0.0.1 reaches the
// station with "Host: evil.example"; every request under a name not the station's is refused.
TEST_F(RequestGuardTest, RefusesRequestsUnderANameThatIsNotTheStations) {
  for (const char* path : {"/api/maps", "/api/maps/map", "/"}) {
    auto r = client_->Get(path, {{"Host", "evil.example:" + std::to_string(port_)}});
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 403) << path;
    const json j = json::parse(r->body, nullptr, false);
    EXPECT_EQ(j["error"]["code"], "forbidden-host") << r->body;
    EXPECT_THAT(j["error"]["message"].get<std::string>(),
                HasSubstr("start `sewerplan serve` with --allow-host evil.example"));
  }
  auto r = client_->Post("/api/maps?name=x.json", {{"Host", "evil.example"}},
                         read(kAis / "map.json"), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_EQ(map_count(), 1u);
  // The station's own names: an address (any IP literal: rebinding needs a name), localhost.
  for (const std::string& host :
       {here(), "localhost:" + std::to_string(port_), "[::1]:" + std::to_string(port_),
        std::string("LOCALHOST"), std::string("192.168.1.20:9000")}) {
    auto ok = client_->Get("/api/maps", {{"Host", host}});
    ASSERT_TRUE(ok) << host;
    EXPECT_EQ(ok->status, 200) << host << ": " << ok->body;
  }
  // No Host at all (HTTP/1.0): refused too.
  RawConnection raw(port_);
  ASSERT_TRUE(raw.connected());
  ASSERT_TRUE(raw.send("GET /api/maps HTTP/1.0\r\n\r\n"));
  const std::string answer = raw.receive(30);
  EXPECT_THAT(answer, HasSubstr("HTTP/1.1 403"));
  EXPECT_EQ(body_of(answer)["error"]["code"], "forbidden-host");
}

TEST_F(RequestGuardTest, ManualAnswersUnderTheNamesTheOperatorAllowed) {
  start({.host = "127.0.0.1", .allowed_hosts = {"Station.lan"}});
  auto r = client_->Get("/api/maps", {{"Host", "station.LAN:8080"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  r = client_->Get("/api/maps", {{"Host", "other.lan:8080"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
}

// A page of another site posts to the station: the browser sends its Origin, and the station
// refuses it before the body is read, whatever the body's type; its preflight gets no CORS grant.
TEST_F(RequestGuardTest, RefusesACrossOriginPostAndItsPreflight) {
  auto r = client_->Post("/api/maps?name=x.json", {{"Origin", "http://evil.example"}},
                         read(kAis / "map.json"), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_EQ(json::parse(r->body)["error"]["code"], "forbidden-origin");
  EXPECT_THAT(json::parse(r->body)["error"]["message"].get<std::string>(),
              HasSubstr("Origin 'http://evil.example' is not this station's (http://" + here()));
  // The "simple" POST of the issue: text/plain, no preflight; a campaign was started by it.
  const json campaign = {{"mission", json::parse(read(kAis / "missions/paper.json"))},
                         {"runs", 10000}};
  r = client_->Post("/api/maps/map/campaign", {{"Origin", "http://evil.example"}}, campaign.dump(),
                    "text/plain");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_EQ(get("/api/campaign").second["state"], "none");
  // A sandboxed page's Origin.
  r = client_->Post("/api/maps/map/validate", {{"Origin", "null"}},
                    read(kAis / "missions/paper.json"), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  // The preflight of a cross-origin JSON POST.
  httplib::Request preflight;
  preflight.method = "OPTIONS";
  preflight.path = "/api/maps/map/plan";
  preflight.headers = {{"Origin", "http://evil.example"},
                       {"Access-Control-Request-Method", "POST"},
                       {"Access-Control-Request-Headers", "content-type"}};
  auto p = client_->send(preflight);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->status, 403);
  EXPECT_FALSE(p->has_header("Access-Control-Allow-Origin"));
  // PUT, DELETE, PATCH: not the station's methods.
  auto put = client_->Put("/api/maps", "{}", "application/json");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 405);
  EXPECT_THAT(put->body, HasSubstr("GET, HEAD and POST only"));
  EXPECT_EQ(client_->Delete("/api/maps/map")->status, 405);
  EXPECT_EQ(client_->Patch("/api/maps/map", "{}", "application/json")->status, 405);
  // The station's own page: its Origin is http:// and the Host.
  r = client_->Post("/api/maps/map/validate", {{"Origin", "http://" + here()}},
                    read(kAis / "missions/paper.json"), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
}

// A page may send text/plain, a form or no type to any site unasked: such a POST is refused
// (415), so a page of another site must ask first (a preflight), and is refused then.
TEST_F(RequestGuardTest, RefusesAPostOfATypeAPageMaySendUnasked) {
  const std::string mission = read(kAis / "missions/paper.json");
  for (const char* type :
       {"text/plain", "text/plain; charset=UTF-8", "application/x-www-form-urlencoded",
        "multipart/form-data; boundary=x", "application/xml"}) {
    auto r = client_->Post("/api/maps/map/plan", mission, type);
    ASSERT_TRUE(r) << type;
    EXPECT_EQ(r->status, 415) << type;
    const json j = json::parse(r->body, nullptr, false);
    EXPECT_EQ(j["error"]["code"], "unsupported-media-type");
    EXPECT_THAT(j["error"]["message"].get<std::string>(),
                HasSubstr("POST /api/maps/map/plan needs \"Content-Type: application/json\""));
  }
  auto r = client_->Post("/api/maps/map/plan", mission, "Application/JSON; charset=utf-8");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  // No type at all: the campaign's cancel too (it has no body).
  RawConnection raw(port_);
  ASSERT_TRUE(raw.send("POST /api/campaign/cancel HTTP/1.1\r\nHost: " + here() +
                       "\r\nContent-Length: 0\r\n\r\n"));
  const std::string answer = raw.receive(30);
  EXPECT_THAT(answer, HasSubstr("HTTP/1.1 415"));
  EXPECT_THAT(body_of(answer)["error"]["message"].get<std::string>(), HasSubstr("not none"));
  // An uploaded file goes as it is, with its own type, but not one a page may send unasked.
  const std::string inp = read(kSource / "datasets/swmm/epa-example1.inp");
  r = client_->Post("/api/maps?name=epa-example1.inp", inp, "text/plain");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 415);
  EXPECT_THAT(json::parse(r->body)["error"]["message"].get<std::string>(),
              HasSubstr("needs the file's own Content-Type"));
  EXPECT_EQ(client_->Post("/api/maps/map/replay", "", "multipart/form-data")->status, 415);
  EXPECT_EQ(map_count(), 1u);
  r = client_->Post("/api/maps?name=epa-example1.inp", inp, "application/octet-stream");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201) << r->body;
}

// A chunked body carries no length: the station reads it and stops at the limit, answering 413
// before the client has sent it all (it never does here).
TEST_F(RequestGuardTest, ManualRefusesAChunkedBodyOverTheLimitWithoutReadingItWhole) {
  start({.max_body_bytes = 1u << 20});
  for (const char* path : {"/api/maps/map/validate", "/api/maps?name=big.json"}) {
    RawConnection raw(port_);
    ASSERT_TRUE(raw.connected());
    ASSERT_TRUE(raw.send(std::string("POST ") + path + " HTTP/1.1\r\nHost: " + here() +
                         "\r\nContent-Type: application/json\r\nTransfer-Encoding: "
                         "chunked\r\n\r\n"));
    // 1.5 MiB in 64 KiB chunks, and no last chunk: a station that reads the body whole waits.
    std::thread sender([&raw] {
      const std::string chunk = "10000\r\n" + std::string(0x10000, ' ') + "\r\n";
      for (int i = 0; i < 24 && raw.send(chunk); ++i) {
      }
    });
    const std::string answer = raw.receive(30);
    sender.join();
    EXPECT_THAT(answer, HasSubstr("HTTP/1.1 413")) << path;
    EXPECT_EQ(body_of(answer)["error"]["message"],
              "the request body is over the size limit of 1048576 bytes")
        << answer;
  }
  // An endpoint that is not there: a 404 without the body read.
  RawConnection raw(port_);
  ASSERT_TRUE(raw.send("POST /api/nothing HTTP/1.1\r\nHost: " + here() +
                       "\r\nContent-Type: application/json\r\nTransfer-Encoding: "
                       "chunked\r\n\r\n10000\r\n" +
                       std::string(0x10000, ' ') + "\r\n"));
  EXPECT_THAT(raw.receive(30), HasSubstr("HTTP/1.1 404"));
  EXPECT_EQ(map_count(), 1u);
}

// A Content-Length over the limit is refused before the body is sent; with
// "Expect: 100-continue" (curl's, for a large body) the client is told so before it sends.
TEST_F(RequestGuardTest, ManualRefusesALengthOverTheLimitBeforeTheBody) {
  start({.max_body_bytes = 1000});
  for (const char* expect : {"", "Expect: 100-continue\r\n"}) {
    RawConnection raw(port_);
    ASSERT_TRUE(raw.send("POST /api/maps/map/validate HTTP/1.1\r\nHost: " + here() +
                         "\r\nContent-Type: application/json\r\nContent-Length: 1073741824\r\n" +
                         expect + "\r\n"));
    const std::string answer = raw.receive(30);
    EXPECT_THAT(answer, HasSubstr("HTTP/1.1 413")) << expect;
    EXPECT_THAT(answer, ::testing::Not(HasSubstr("100 Continue")));
    EXPECT_EQ(body_of(answer)["error"]["message"],
              "the request body is over the size limit of 1000 bytes");
  }
}

// gzip: 2 MiB of spaces in about 2 kB. The limit counts what the body decompresses to.
TEST_F(RequestGuardTest, ManualRefusesACompressedBodyThatDecompressesOverTheLimit) {
  start({.max_body_bytes = 1u << 20});
  const std::string plain(2u << 20, ' ');
  z_stream z{};
  ASSERT_EQ(deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string gzip(deflateBound(&z, plain.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(plain.data()));
  z.avail_in = static_cast<uInt>(plain.size());
  z.next_out = reinterpret_cast<Bytef*>(gzip.data());
  z.avail_out = static_cast<uInt>(gzip.size());
  ASSERT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  gzip.resize(z.total_out);
  deflateEnd(&z);
  ASSERT_LT(gzip.size(), 10000u);
  auto r = client_->Post("/api/maps/map/validate", {{"Content-Encoding", "gzip"}}, gzip,
                         "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413) << r->body;
}

// Connections that send nothing, or a byte a second and never a whole request, need no token:
// each holds a worker while it is open. A request of the operator's is still answered.
TEST_F(RequestGuardTest, AnswersWhileManyConnectionsSitIdleOrTrickle) {
  // Half of them start a request at once and add to its headers a byte a second, from the start
  // and as long as the test runs; the other half send nothing.
  constexpr std::size_t kConnections = 100;
  std::vector<std::unique_ptr<RawConnection>> idle(kConnections);
  std::atomic<std::size_t> opened{0};
  std::atomic<bool> done{false};
  std::thread trickle([&] {
    while (!done) {
      for (std::size_t i = 0; i < opened; i += 2) idle[i]->send("x");
      std::this_thread::sleep_for(std::chrono::seconds(1));
    }
  });
  for (std::size_t i = 0; i < kConnections; ++i) {
    idle[i] = std::make_unique<RawConnection>(port_);
    EXPECT_TRUE(idle[i]->connected());
    if (i % 2 == 0) {
      EXPECT_TRUE(idle[i]->send("GET /api/maps HTTP/1.1\r\nHost: " + here() + "\r\nX-Slow: "));
    }
    ++opened;
  }
  httplib::Client client("127.0.0.1", port_);
  client.set_read_timeout(60, 0);
  auto r = client.Get("/api/maps");
  done = true;
  trickle.join();
  ASSERT_TRUE(r) << "no answer within 60 s: " << r.error();
  EXPECT_EQ(r->status, 200);
}

// More connections than the station serves at once, each trickling a byte every 100 ms (within
// the read timeout) and never ending its request, held every worker for as long as they went on:
// httplib times out each read, not the request. Each is closed at its deadline (the headers', or
// the whole request's for a POST's body), and a request of the operator's, waiting its turn behind
// them, is answered.
TEST_F(RequestGuardTest, ManualAnswersWhileMoreConnectionsThanWorkersTrickle) {
  start({.max_connections = 8, .headers_deadline_s = 0.5, .request_deadline_s = 0.6});
  // Half trickle their headers, half the body of a POST whose headers came whole.
  constexpr std::size_t kConnections = 20;
  std::vector<std::unique_ptr<RawConnection>> slow;
  for (std::size_t i = 0; i < kConnections; ++i) {
    slow.push_back(std::make_unique<RawConnection>(port_));
    ASSERT_TRUE(slow.back()->connected());
    ASSERT_TRUE(slow.back()->send(
        i % 2 == 0 ? "GET /api/maps HTTP/1.1\r\nHost: " + here() + "\r\nX-Slow: "
                   : "POST /api/maps/map/validate HTTP/1.1\r\nHost: " + here() +
                         "\r\nContent-Type: application/json\r\nContent-Length: 100000\r\n\r\n"));
  }
  std::atomic<bool> done{false};
  std::atomic<std::size_t> cut{0};
  std::thread trickle([&] {
    std::vector<bool> closed(kConnections, false);
    while (!done) {
      for (std::size_t i = 0; i < kConnections; ++i) {
        if (!closed[i] && !slow[i]->send("x")) closed[i] = true, ++cut;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  // Younger than the trickling ones: its wait for a worker counts against its own deadline.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  httplib::Client client("127.0.0.1", port_);
  client.set_read_timeout(10, 0);
  auto r = client.Get("/api/maps");
  // Each trickling connection closed by the station: its sends fail (a reset) soon after.
  for (int i = 0; i < 50 && cut < kConnections; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  done = true;
  trickle.join();
  ASSERT_TRUE(r) << "no answer within 10 s: " << r.error();
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(cut, kConnections);
}

// httplib binds with SO_REUSEPORT: a second server, of any program of the same user, bound the
// station's port and was given half its connections. The station's port is its own.
TEST_F(RequestGuardTest, KeepsItsPortToItself) {
  ServerOptions options;
  options.maps = {kAis / "map.json"};
  options.port = port_;
  Result<std::unique_ptr<StationServer>> second = StationServer::create(options);
  ASSERT_TRUE(second.has_value()) << second.error();
  const Result<int> bound = (*second)->bind();
  ASSERT_FALSE(bound.has_value()) << "a second server bound port " << port_;
  EXPECT_THAT(bound.error().message, HasSubstr("cannot listen on 127.0.0.1:"));
}

TEST(WorkerPool, StartsAWorkerForEachJobThatWouldWaitUpToItsLimit) {
  WorkerPool pool(8);
  std::atomic<int> running{0};
  std::atomic<bool> release{false};
  for (int i = 0; i < 8; ++i) {
    pool.enqueue([&] {
      ++running;
      while (!release) std::this_thread::yield();
    });
  }
  // Eight jobs that wait for each other: only eight workers let them all run at once.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (running < 8 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  EXPECT_EQ(running, 8);
  std::atomic<int> later{0};
  pool.enqueue([&] { ++later; });  // beyond the limit: runs once a worker is free
  release = true;
  pool.shutdown();
  EXPECT_EQ(later, 1);
}

}  // namespace
}  // namespace sewerplan::server
