#pragma once
// glint/video/packet.h — a compressed packet, passed through the video layer untouched
// (a copied audio stream): FFmpeg's AVPacket behind a move-only owner.

struct AVPacket;  // FFmpeg's; only pointers to it appear here

namespace glint::video {

/// A compressed packet (audio passed through without decoding). Move-only.
class Packet {
public:
  Packet() = default;
  /// Takes ownership of `packet` (freed with av_packet_free).
  explicit Packet(AVPacket* packet);
  ~Packet();
  Packet(Packet&& other) noexcept;
  Packet& operator=(Packet&& other) noexcept;
  Packet(const Packet&) = delete;
  Packet& operator=(const Packet&) = delete;

  AVPacket* get() const { return m_packet; }
  explicit operator bool() const { return m_packet != nullptr; }

private:
  AVPacket* m_packet = nullptr;
};

}  // namespace glint::video
