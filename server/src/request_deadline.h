// SPDX-License-Identifier: MIT
// A deadline for a whole request: httplib (0.11) times out each read of a connection, not the
// request, so a connection that sends a byte every few seconds and never ends its headers (or its
// body) holds its worker for as long as it likes, and `max_connections` of them held every worker
// (docs/operator-station.md, "Connections"). This watch cuts such a connection: every `period` it
// lists the process's connections to the station's port (its file descriptors, getsockname and
// getpeername: httplib hands our code no socket before the request is read), notes when it first
// saw each, and shuts down (shutdown(2): the worker's read ends, httplib closes it) one whose
// headers have not been read `headers` after, or whose request (a POST's body too) has not been
// read whole `whole` after. The station's handlers report both (headers_read(), read_whole(), with
// the request's remote address and port); from then on the connection is the handler's (a stream
// may last an hour). A connection waiting for a worker counts its wait against its deadlines.
// Private to server/src.
//
//   RequestDeadline watch(port, std::chrono::seconds(10), std::chrono::seconds(60));
//   watch.start();                              // a thread of its own
//   watch.headers_read(req.remote_addr, req.remote_port);
//   watch.read_whole(req.remote_addr, req.remote_port);
//
// Thread safety: read_whole() from any thread; start() and stop() from one.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace sewerplan::server {

class RequestDeadline {
 public:
  RequestDeadline(int port, std::chrono::milliseconds headers, std::chrono::milliseconds whole);
  ~RequestDeadline();
  RequestDeadline(const RequestDeadline&) = delete;
  RequestDeadline& operator=(const RequestDeadline&) = delete;

  void start();
  void stop();
  // The request of the connection from `address`:`port` has its headers read, or is read whole.
  void headers_read(const std::string& address, int port);
  void read_whole(const std::string& address, int port);
  // Connections cut so far.
  std::size_t cut() const { return cut_; }

 private:
  struct Seen {
    std::chrono::steady_clock::time_point since;
    bool headers = false;
    bool read = false;
    bool present = false;  // in the last listing
  };
  void watch();
  void sweep();
  void mark(const std::string& address, int port, bool whole);

  const int port_;
  const std::chrono::milliseconds headers_;
  const std::chrono::milliseconds whole_;
  const std::chrono::milliseconds period_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, Seen> connections_;  // "address port" of the peer
  bool stopping_ = false;
  std::atomic<std::size_t> cut_{0};
  std::thread thread_;
};

}  // namespace sewerplan::server
