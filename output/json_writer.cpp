#include "output/json_writer.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace wl {
namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0 if invalid.
size_t utf8_length(std::string_view s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  size_t n;
  unsigned min;
  unsigned cp;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0) {
    n = 2;
    cp = c & 0x1F;
    min = 0x80;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3;
    cp = c & 0x0F;
    min = 0x800;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4;
    cp = c & 0x07;
    min = 0x10000;
  } else return 0;
  if (i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;  // overlong, too large, surrogate
  return n;
}

void append_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest round-trip form
  out.append(buf, r.ptr);
}

void newline(std::string& out, int indent, int depth) {
  out += '\n';
  out.append(static_cast<size_t>(indent * depth), ' ');
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

}  // namespace

std::string json_quote(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '"';
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '"':
        out += "\\\"";
        ++i;
        continue;
      case '\\':
        out += "\\\\";
        ++i;
        continue;
      case '\n':
        out += "\\n";
        ++i;
        continue;
      case '\r':
        out += "\\r";
        ++i;
        continue;
      case '\t':
        out += "\\t";
        ++i;
        continue;
      case '\b':
        out += "\\b";
        ++i;
        continue;
      case '\f':
        out += "\\f";
        ++i;
        continue;
      default: break;
    }
    if (u < 0x20 || u == 0x7F) {
      static const char* hex = "0123456789abcdef";
      out += "\\u00";
      out += hex[u >> 4];
      out += hex[u & 0xF];
      ++i;
      continue;
    }
    const size_t n = utf8_length(text, i);
    if (n == 0) {
      out += "\\ufffd";  // invalid UTF-8 byte
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  out += '"';
  return out;
}

Json::Json(const std::vector<double>& xs) : kind_(Kind::array) {
  items_.reserve(xs.size());
  for (double x : xs) items_.emplace_back(x);
}

Json::Json(const std::vector<std::string>& xs) : kind_(Kind::array) {
  items_.reserve(xs.size());
  for (const std::string& x : xs) items_.emplace_back(x);
}

Json::Json(const std::map<std::string, std::string>& entries) : kind_(Kind::object) {
  for (const auto& [k, v] : entries) members_.emplace_back(k, Json(v));
}

Json& Json::set(const std::string& key, Json value) {
  (*this)[key] = std::move(value);
  return *this;
}

Json& Json::operator[](const std::string& key) {
  if (kind_ == Kind::null) kind_ = Kind::object;
  if (kind_ != Kind::object) throw std::logic_error("Json: key '" + key + "' used on a value that is not an object");
  for (auto& [k, v] : members_)
    if (k == key) return v;
  members_.emplace_back(key, Json());
  return members_.back().second;
}

Json& Json::push(Json value) {
  if (kind_ == Kind::null) kind_ = Kind::array;
  if (kind_ != Kind::array) throw std::logic_error("Json: push() on a value that is not an array");
  items_.push_back(std::move(value));
  return *this;
}

size_t Json::size() const { return kind_ == Kind::array ? items_.size() : kind_ == Kind::object ? members_.size() : 0; }

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  out += '\n';
  return out;
}

void Json::dump_to(std::string& out, int indent, int depth) const {
  switch (kind_) {
    case Kind::null: out += "null"; return;
    case Kind::boolean: out += bool_ ? "true" : "false"; return;
    case Kind::integer: out += std::to_string(int_); return;
    case Kind::number: append_number(out, number_); return;
    case Kind::string: out += json_quote(string_); return;
    case Kind::array: {
      if (items_.empty()) {
        out += "[]";
        return;
      }
      bool flat = true;  // arrays of scalars on one line: [0, 0, -9.81]
      for (const Json& j : items_) flat = flat && !j.is_container();
      out += '[';
      for (size_t k = 0; k < items_.size(); ++k) {
        if (k) out += flat ? ", " : ",";
        if (!flat) newline(out, indent, depth + 1);
        items_[k].dump_to(out, indent, depth + 1);
      }
      if (!flat) newline(out, indent, depth);
      out += ']';
      return;
    }
    case Kind::object: {
      if (members_.empty()) {
        out += "{}";
        return;
      }
      out += '{';
      for (size_t k = 0; k < members_.size(); ++k) {
        if (k) out += ',';
        newline(out, indent, depth + 1);
        out += json_quote(members_[k].first);
        out += ": ";
        members_[k].second.dump_to(out, indent, depth + 1);
      }
      newline(out, indent, depth);
      out += '}';
      return;
    }
  }
}

std::map<std::string, std::string> machine_info() {
  std::map<std::string, std::string> info;
  char host[256] = {};
  info["hostname"] = (::gethostname(host, sizeof host - 1) == 0 && host[0]) ? host : "unknown";
  struct utsname u {};
  info["os"] = (::uname(&u) == 0) ? std::string(u.sysname) + " " + u.release + " " + u.machine : "unknown";
  info["cpu_model"] = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim(line.substr(0, colon));
    if (key == "model name" || key == "Hardware" || key == "Model" || key == "cpu") {  // x86, ARM, POWER
      const std::string value = trim(line.substr(colon + 1));
      if (!value.empty()) {
        info["cpu_model"] = value;
        if (key == "model name") break;
      }
    }
  }
  const unsigned cores = std::thread::hardware_concurrency();
  info["cpu_cores"] = cores ? std::to_string(cores) : "unknown";
#if defined(__clang__)
  info["compiler"] = __VERSION__;  // already names Clang
#elif defined(__GNUC__)
  info["compiler"] = "GCC " __VERSION__;
#else
  info["compiler"] = __VERSION__;
#endif
  return info;
}

}  // namespace wl
