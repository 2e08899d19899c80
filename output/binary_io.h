// Plain little-endian records of the experiment caches (the reference
// trajectory of docs/design.md §7.3, the fidelity reference of §7.5): values
// appended to a byte string as the machine holds them, read back in order.
#pragma once
#include <cstdint>
#include <istream>
#include <string>

namespace wl {

template <class T>
void put(std::string& out, const T& x) {
  out.append(reinterpret_cast<const char*>(&x), sizeof(T));
}

template <class T>
bool get(std::istream& in, T& x) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&x), sizeof(T)));
}

// A string as its length (u64) and bytes.
inline void put_string(std::string& out, const std::string& s) {
  put<std::uint64_t>(out, s.size());
  out += s;
}

// Reads a string written by put_string; false beyond `max_size` bytes (a file that is not ours).
inline bool get_string(std::istream& in, std::string& s, std::uint64_t max_size = 1u << 24) {
  std::uint64_t n = 0;
  if (!get(in, n) || n > max_size) return false;
  s.assign(n, '\0');
  return static_cast<bool>(in.read(s.data(), static_cast<std::streamsize>(n)));
}

}  // namespace wl
