// SPDX-License-Identifier: MIT
#include "request_deadline.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

#include <dirent.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>

namespace sewerplan::server {
namespace {

// The port of a TCP address (IPv4 or IPv6), or -1.
int port_of(const sockaddr_storage& address) {
  if (address.ss_family == AF_INET) {
    return ntohs(reinterpret_cast<const sockaddr_in&>(address).sin_port);
  }
  if (address.ss_family == AF_INET6) {
    return ntohs(reinterpret_cast<const sockaddr_in6&>(address).sin6_port);
  }
  return -1;
}

// "address port" of the peer of `fd` if it is a connection to our `port`, as httplib writes a
// request's remote_addr (getnameinfo, numeric) and remote_port.
std::optional<std::string> peer_of(int fd, int port) {
  sockaddr_storage local{};
  socklen_t size = sizeof local;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &size) != 0 ||
      port_of(local) != port) {
    return std::nullopt;
  }
  sockaddr_storage peer{};
  size = sizeof peer;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &size) != 0) return std::nullopt;
  char host[NI_MAXHOST];
  if (::getnameinfo(reinterpret_cast<const sockaddr*>(&peer), size, host, sizeof host, nullptr, 0,
                    NI_NUMERICHOST) != 0) {
    return std::nullopt;
  }
  return std::string(host) + " " + std::to_string(port_of(peer));
}

}  // namespace

RequestDeadline::RequestDeadline(int port, std::chrono::milliseconds headers,
                                 std::chrono::milliseconds whole)
    : port_(port),
      headers_(headers),
      whole_(whole),
      period_(std::clamp(std::min(headers, whole) / 4, std::chrono::milliseconds(10),
                         std::chrono::milliseconds(1000))) {}

RequestDeadline::~RequestDeadline() { stop(); }

void RequestDeadline::start() {
  if (!thread_.joinable()) thread_ = std::thread([this] { watch(); });
}

void RequestDeadline::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void RequestDeadline::headers_read(const std::string& address, int port) {
  mark(address, port, false);
}
void RequestDeadline::read_whole(const std::string& address, int port) {
  mark(address, port, true);
}

void RequestDeadline::mark(const std::string& address, int port, bool whole) {
  const std::lock_guard lock(mutex_);
  Seen& seen = connections_[address + " " + std::to_string(port)];
  if (!seen.present) seen.since = std::chrono::steady_clock::now();
  seen.headers = true;
  seen.read = seen.read || whole;
  seen.present = true;
}

void RequestDeadline::watch() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, period_, [this] { return stopping_; });
    if (stopping_) return;
    lock.unlock();
    sweep();
    lock.lock();
  }
}

void RequestDeadline::sweep() {
  // The process's connections to the port now: file descriptor and peer.
  std::vector<std::pair<int, std::string>> open;
  if (DIR* fds = ::opendir("/proc/self/fd")) {
    while (const dirent* entry = ::readdir(fds)) {
      char* end = nullptr;
      const long fd = std::strtol(entry->d_name, &end, 10);
      if (end == entry->d_name || *end != '\0' || fd == ::dirfd(fds)) continue;
      if (std::optional<std::string> peer = peer_of(static_cast<int>(fd), port_)) {
        open.emplace_back(static_cast<int>(fd), std::move(*peer));
      }
    }
    ::closedir(fds);
  }
  const auto now = std::chrono::steady_clock::now();
  std::vector<std::pair<int, std::string>> late;
  {
    const std::lock_guard lock(mutex_);
    for (auto& [key, seen] : connections_) seen.present = false;
    for (const auto& [fd, peer] : open) {
      auto [it, fresh] = connections_.try_emplace(peer, Seen{.since = now});
      it->second.present = true;
      const Seen& seen = it->second;
      const auto age = now - seen.since;
      if ((!seen.headers && age >= headers_) || (!seen.read && age >= whole_)) {
        late.emplace_back(fd, peer);
      }
    }
    // Connections gone (closed) are forgotten: a new one from the same peer port starts afresh.
    std::erase_if(connections_, [](const auto& entry) { return !entry.second.present; });
  }
  for (const auto& [fd, peer] : late) {
    // The descriptor may have been closed and given to another connection since the listing:
    // only the same peer is cut.
    if (peer_of(fd, port_) == peer && ::shutdown(fd, SHUT_RDWR) == 0) ++cut_;
  }
}

}  // namespace sewerplan::server
