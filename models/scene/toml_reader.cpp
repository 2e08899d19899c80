#include "models/scene/toml_reader.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <sstream>

namespace wl::scene_detail {

namespace {

// Byte offset of 1-based code-point column `col` in `line` (toml++ counts code points).
size_t byte_of_column(const std::string& line, int col) {
  size_t b = 0;
  for (int c = 1; c < col && b < line.size(); ++c) {
    ++b;
    while (b < line.size() && (static_cast<unsigned char>(line[b]) & 0xC0) == 0x80) ++b;
  }
  return std::min(b, line.size());
}

std::string trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string_view::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(a, b - a + 1));
}

std::string shorten(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  constexpr size_t max_len = 80;
  if (s.size() > max_len) s = s.substr(0, max_len - 3) + "...";
  return s;
}

std::string join(const std::vector<std::string>& v, std::string_view sep) {
  std::string r;
  for (size_t k = 0; k < v.size(); ++k) r += (k ? std::string(sep) : std::string()) + v[k];
  return r;
}

}  // namespace

Source::Source(std::string_view text, std::string file) : file_(std::move(file)) {
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      lines_.emplace_back(text.substr(start));
      break;
    }
    lines_.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
}

std::string Source::line_text(int line) const {
  if (line < 1 || line > static_cast<int>(lines_.size())) return "";
  return trim(lines_[line - 1]);
}

std::string Source::written(const toml::node& n) const {
  const toml::source_region& r = n.source();
  const int l0 = static_cast<int>(r.begin.line), l1 = static_cast<int>(r.end.line);
  if (l0 < 1 || l1 < l0 || l1 > static_cast<int>(lines_.size())) {
    // No usable source position: format the value instead.
    std::ostringstream os;
    os << toml::toml_formatter(n);
    return shorten(os.str());
  }
  std::string s;
  for (int l = l0; l <= l1; ++l) {
    const std::string& line = lines_[l - 1];
    const size_t a = l == l0 ? byte_of_column(line, r.begin.column) : 0;
    const size_t b = l == l1 ? byte_of_column(line, r.end.column) : line.size();
    if (l > l0) s += ' ';
    s += trim(std::string_view(line).substr(a, b > a ? b - a : 0));
  }
  return shorten(s);
}

void Source::fail(int line, std::string key, std::string value, std::string expected) const {
  throw SceneError(file_, line, std::move(key), std::move(value), std::move(expected));
}

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

std::string format_number(double x) {
  // Shortest round-trip digits; fixed notation for ordinary magnitudes.
  char buf[400];
  const double a = std::abs(x);
  const bool fixed = a == 0.0 || (a >= 1e-4 && a < 1e7);
  const auto res =
      std::to_chars(buf, buf + sizeof buf, x, fixed ? std::chars_format::fixed : std::chars_format::scientific);
  return std::string(buf, res.ptr);
}

TableReader::TableReader(const Source& src, const toml::table& table, std::string path)
    : src_(src), table_(table), path_(std::move(path)) {}

std::string TableReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string TableReader::describe() const { return path_.empty() ? "the top level" : "[" + path_ + "]"; }

const toml::node* TableReader::get(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  return table_.get(key);
}

void TableReader::fail_at(const toml::node& n, std::string_view key, const std::string& expected) const {
  src_.fail(line_of(n), key_path(key), src_.written(n), expected);
}

void TableReader::fail_missing(std::string_view key, const std::string& expected) const {
  src_.fail(line(), key_path(key), "nothing (key missing)", expected);
}

void TableReader::fail_key(std::string_view key, const std::string& expected, const std::string& default_value) const {
  if (const toml::node* n = table_.get(key)) fail_at(*n, key, expected);
  src_.fail(line(), key_path(key), default_value + " (the default)", expected);
}

void TableReader::declare(const std::vector<std::string>& keys) {
  for (const auto& k : keys) get(k);
}

bool TableReader::read_number(std::string_view key, double& out, const std::string& expected,
                              const std::function<bool(double)>& ok) {
  const toml::node* n = get(key);
  if (!n) return false;
  double x;
  if (const auto* i = n->as_integer()) x = static_cast<double>(i->get());
  else if (const auto* f = n->as_floating_point()) x = f->get();
  else fail_at(*n, key, expected);
  if (!std::isfinite(x) || (ok && !ok(x))) fail_at(*n, key, expected);
  out = x;
  return true;
}

bool TableReader::read_number(std::string_view key, std::optional<double>& out, const std::string& expected,
                              const std::function<bool(double)>& ok) {
  double x = 0.0;
  if (!read_number(key, x, expected, ok)) return false;
  out = x;
  return true;
}

bool TableReader::read_int(std::string_view key, int& out, const std::string& expected,
                           const std::function<bool(long long)>& ok) {
  const toml::node* n = get(key);
  if (!n) return false;
  const auto* i = n->as_integer();  // 17.0 is a float and therefore rejected
  if (!i) fail_at(*n, key, expected);
  const long long x = i->get();
  if (x < INT_MIN || x > INT_MAX || (ok && !ok(x))) fail_at(*n, key, expected);
  out = static_cast<int>(x);
  return true;
}

bool TableReader::read_bool(std::string_view key, bool& out) {
  const toml::node* n = get(key);
  if (!n) return false;
  const auto* b = n->as_boolean();
  if (!b) fail_at(*n, key, "true or false");
  out = b->get();
  return true;
}

bool TableReader::read_string(std::string_view key, std::string& out, const std::string& expected,
                              const std::function<bool(const std::string&)>& ok) {
  const toml::node* n = get(key);
  if (!n) return false;
  const auto* s = n->as_string();
  if (!s || (ok && !ok(s->get()))) fail_at(*n, key, expected);
  out = s->get();
  return true;
}

bool TableReader::read_choice(std::string_view key, int& out, const std::vector<std::string>& names) {
  std::vector<std::string> quoted;
  for (const auto& s : names) quoted.push_back('"' + s + '"');
  const std::string expected = "one of " + join(quoted, ", ");
  std::string s;
  if (!read_string(key, s, expected)) return false;
  const auto it = std::find(names.begin(), names.end(), s);
  if (it == names.end()) fail_at(*table_.get(key), key, expected);
  out = static_cast<int>(it - names.begin());
  return true;
}

bool TableReader::read_number_array(std::string_view key, std::vector<double>& out, const std::string& expected,
                                    const std::function<bool(const std::vector<double>&)>& ok) {
  const toml::node* n = get(key);
  if (!n) return false;
  const auto* a = n->as_array();
  if (!a) fail_at(*n, key, expected);
  std::vector<double> v;
  for (const toml::node& e : *a) {
    if (const auto* i = e.as_integer()) v.push_back(static_cast<double>(i->get()));
    else if (const auto* f = e.as_floating_point()) v.push_back(f->get());
    else fail_at(*n, key, expected);
    if (!std::isfinite(v.back())) fail_at(*n, key, expected);
  }
  if (ok && !ok(v)) fail_at(*n, key, expected);
  out = std::move(v);
  return true;
}

bool TableReader::read_vec3(std::string_view key, std::array<double, 3>& out, const std::string& expected) {
  std::vector<double> v;
  if (!read_number_array(key, v, expected, [](const std::vector<double>& x) { return x.size() == 3; })) return false;
  std::copy(v.begin(), v.end(), out.begin());
  return true;
}

bool TableReader::read_string_array(std::string_view key, std::vector<std::string>& out, const std::string& expected) {
  const toml::node* n = get(key);
  if (!n) return false;
  const auto* a = n->as_array();
  if (!a || a->empty()) fail_at(*n, key, expected);
  std::vector<std::string> v;
  for (const toml::node& e : *a) {
    const auto* s = e.as_string();
    if (!s || s->get().empty()) fail_at(*n, key, expected);
    v.push_back(s->get());
  }
  out = std::move(v);
  return true;
}

std::optional<TableReader> TableReader::subtable(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  const auto* t = n->as_table();
  if (!t) fail_at(*n, key, "a table [" + key_path(key) + "]");
  return TableReader(src_, *t, key_path(key));
}

std::vector<TableReader> TableReader::table_array(std::string_view key) {
  const toml::node* n = get(key);
  std::vector<TableReader> r;
  if (!n) return r;
  const std::string expected = "an array of tables [[" + key_path(key) + "]]";
  const auto* a = n->as_array();
  if (!a) fail_at(*n, key, expected);
  for (size_t k = 0; k < a->size(); ++k) {
    const auto* t = a->get(k)->as_table();
    if (!t) fail_at(*a->get(k), key, expected);
    r.emplace_back(src_, *t, key_path(key) + "[" + std::to_string(k) + "]");
  }
  return r;
}

void TableReader::accept_all_keys() {
  for (auto&& [k, v] : table_) get(k.str());
}

void TableReader::finish(const std::string& note) const {
  const toml::node* worst = nullptr;
  std::string worst_key;
  for (auto&& [k, v] : table_) {
    if (std::find(known_.begin(), known_.end(), k.str()) != known_.end()) continue;
    if (!worst || line_of(v) < line_of(*worst)) {
      worst = &v;
      worst_key = std::string(k.str());
    }
  }
  if (!worst) return;
  std::string expected = path_.empty() ? "one of the top-level tables " : "one of the keys of " + describe() + ": ";
  expected += known_.empty() ? std::string("(none)") : join(known_, ", ");
  if (!note.empty()) expected += " " + note;
  fail_at(*worst, worst_key, expected);
}

}  // namespace wl::scene_detail
