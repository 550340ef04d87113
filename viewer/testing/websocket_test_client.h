#pragma once
// A blocking WebSocket client on plain POSIX sockets (RFC 6455: the HTTP upgrade, masked client
// frames, unmasked server frames), for the server's tests. Written out rather than on Beast so
// the test neither shares the server's code nor costs Beast's compile time twice.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace minenav::testing {

class WebSocketTestClient {
 public:
  // Connects to 127.0.0.1:port and upgrades with `protocol` (and Origin `origin` unless empty).
  // Throws std::runtime_error when the server does not answer 101.
  WebSocketTestClient(int port, const std::string& protocol, const std::string& origin = "") {
    fd_ = Connect(port);
    std::string req = "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                      "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n"
                      "Sec-WebSocket-Protocol: " + protocol + "\r\n";
    if (!origin.empty()) req += "Origin: " + origin + "\r\n";
    req += "\r\n";
    SendAll(req);
    std::string head;
    while (head.find("\r\n\r\n") == std::string::npos) {
      char c;
      if (!ReadExact(&c, 1)) throw std::runtime_error("connection closed during the handshake");
      head += c;
    }
    if (head.rfind("HTTP/1.1 101", 0) != 0) throw std::runtime_error("no upgrade: " + head.substr(0, 40));
    const size_t p = head.find("Sec-WebSocket-Protocol: ");
    if (p != std::string::npos) protocol_ = head.substr(p + 24, head.find("\r\n", p) - p - 24);
  }
  ~WebSocketTestClient() { close(fd_); }
  WebSocketTestClient(const WebSocketTestClient&) = delete;
  WebSocketTestClient& operator=(const WebSocketTestClient&) = delete;

  const std::string& protocol() const { return protocol_; }
  bool closed() const { return closed_; }

  // The next data frame's payload; "" when the server closed (closed() is then true) or
  // nothing came for timeout_ms. Pings are answered.
  std::string Next(bool* binary = nullptr, int timeout_ms = 5000) {
    while (true) {
      uint8_t h[2];
      if (!ReadExact(h, 2, timeout_ms)) return "";
      const int opcode = h[0] & 0x0f;
      uint64_t length = h[1] & 0x7f;
      if (length >= 126) {
        uint8_t ext[8];
        const int n = length == 126 ? 2 : 8;
        if (!ReadExact(ext, n, timeout_ms)) return "";
        length = 0;
        for (int i = 0; i < n; ++i) length = (length << 8) | ext[i];
      }
      std::string payload(length, '\0');
      if (length > 0 && !ReadExact(payload.data(), length, timeout_ms)) return "";
      if (opcode == 0x8) {
        closed_ = true;
        return "";
      }
      if (opcode == 0x9) {
        SendFrame(0xA, payload);
        continue;
      }
      if (binary) *binary = opcode == 0x2;
      return payload;
    }
  }
  void SendText(const std::string& s) { SendFrame(0x1, s); }
  void SendBinary(const std::string& s) { SendFrame(0x2, s); }

 private:
  static int Connect(int port) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd < 0 || connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) != 0)
      throw std::runtime_error("cannot connect to 127.0.0.1:" + std::to_string(port));
    return fd;
  }
  void SendAll(const std::string& s) {
    size_t sent = 0;
    while (sent < s.size()) {
      const ssize_t n = send(fd_, s.data() + sent, s.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) throw std::runtime_error("send failed");
      sent += static_cast<size_t>(n);
    }
  }
  // A final frame, masked as a client must (the mask is fixed: tests need no secrecy).
  void SendFrame(int opcode, const std::string& payload) {
    std::string f;
    f.push_back(static_cast<char>(0x80 | opcode));
    const uint64_t n = payload.size();
    if (n < 126) {
      f.push_back(static_cast<char>(0x80 | n));
    } else if (n < 65536) {
      f.push_back(static_cast<char>(0x80 | 126));
      f.push_back(static_cast<char>(n >> 8));
      f.push_back(static_cast<char>(n & 0xff));
    } else {
      f.push_back(static_cast<char>(0x80 | 127));
      for (int i = 7; i >= 0; --i) f.push_back(static_cast<char>((n >> (8 * i)) & 0xff));
    }
    const char mask[4] = {0x12, 0x34, 0x56, 0x78};
    f.append(mask, 4);
    for (size_t i = 0; i < payload.size(); ++i) f.push_back(static_cast<char>(payload[i] ^ mask[i % 4]));
    SendAll(f);
  }
  bool ReadExact(void* out, size_t n, int timeout_ms = 5000) {
    auto* p = static_cast<char*>(out);
    size_t got = 0;
    while (got < n) {
      pollfd pfd{fd_, POLLIN, 0};
      if (poll(&pfd, 1, timeout_ms) <= 0) return false;
      const ssize_t r = recv(fd_, p + got, n - got, 0);
      if (r <= 0) {
        closed_ = true;
        return false;
      }
      got += static_cast<size_t>(r);
    }
    return true;
  }

  int fd_ = -1;
  std::string protocol_;
  bool closed_ = false;
};

}  // namespace minenav::testing
