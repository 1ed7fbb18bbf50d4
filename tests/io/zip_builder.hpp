// Test helper: builds an uncompressed ("stored") ZIP archive in memory, independently of the
// library's libzip code, so that tests can craft X3P files with quirks and damage.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace frictal::test {

inline std::uint32_t crc32(const std::string& s) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : s) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

inline std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& members) {
  auto u16 = [](std::string& o, unsigned v) {
    o += char(v & 0xFF);
    o += char((v >> 8) & 0xFF);
  };
  auto u32 = [](std::string& o, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) o += char((v >> (8 * k)) & 0xFF);
  };
  std::string out, central;
  for (const auto& [name, data] : members) {
    std::uint32_t offset = std::uint32_t(out.size()), crc = crc32(data), size = std::uint32_t(data.size());
    u32(out, 0x04034b50);
    u16(out, 20);
    u16(out, 0);
    u16(out, 0);
    u16(out, 0);
    u16(out, 0x21);
    u32(out, crc);
    u32(out, size);
    u32(out, size);
    u16(out, unsigned(name.size()));
    u16(out, 0);
    out += name;
    out += data;
    u32(central, 0x02014b50);
    u16(central, 20);
    u16(central, 20);
    u16(central, 0);
    u16(central, 0);
    u16(central, 0);
    u16(central, 0x21);
    u32(central, crc);
    u32(central, size);
    u32(central, size);
    u16(central, unsigned(name.size()));
    u16(central, 0);
    u16(central, 0);
    u16(central, 0);
    u16(central, 0);
    u32(central, 0);
    u32(central, offset);
    central += name;
  }
  std::uint32_t cd_offset = std::uint32_t(out.size());
  out += central;
  u32(out, 0x06054b50);
  u16(out, 0);
  u16(out, 0);
  u16(out, unsigned(members.size()));
  u16(out, unsigned(members.size()));
  u32(out, std::uint32_t(central.size()));
  u32(out, cd_offset);
  u16(out, 0);
  return out;
}

}  // namespace frictal::test
