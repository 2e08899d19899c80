// A tiny JSON builder for run summaries (docs/design.md §9):
// objects (keys kept in insertion order), arrays, strings, numbers, bools and
// null, printed with two-space indentation. Plus the machine and the git
// revision that every run summary records.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace wl {

class Json {
 public:
  enum class Kind { null, boolean, integer, number, string, array, object };

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool b) : kind_(Kind::boolean), bool_(b) {}
  template <class I, std::enable_if_t<std::is_integral_v<I> && !std::is_same_v<I, bool>, int> = 0>
  Json(I i) : kind_(Kind::integer), int_(static_cast<std::int64_t>(i)) {}
  Json(double x) : kind_(Kind::number), number_(x) {}
  Json(float x) : Json(static_cast<double>(x)) {}
  Json(const char* s) : kind_(Kind::string), string_(s) {}
  Json(std::string s) : kind_(Kind::string), string_(std::move(s)) {}
  Json(std::string_view s) : kind_(Kind::string), string_(s) {}
  Json(const std::vector<double>& xs);                      // array of numbers
  Json(const std::vector<std::string>& xs);                 // array of strings
  Json(const std::map<std::string, std::string>& entries);  // object of strings

  static Json object() {
    Json j;
    j.kind_ = Kind::object;
    return j;
  }
  static Json array() {
    Json j;
    j.kind_ = Kind::array;
    return j;
  }

  Kind kind() const { return kind_; }
  // Object: sets `key` (replacing an existing value, keeping its position). Throws
  // std::logic_error if this is not an object. Returns *this for chaining.
  Json& set(const std::string& key, Json value);
  // Object: the value at `key`, inserted as null if absent (a null Json becomes an object).
  Json& operator[](const std::string& key);
  // Array: appends. Throws std::logic_error if this is not an array (a null Json becomes an array).
  Json& push(Json value);
  size_t size() const;  // entries of an object or array, else 0

  // Pretty-printed text with `indent` spaces per level and a final newline.
  // Numbers round-trip (shortest representation that reads back exactly);
  // non-finite numbers, which JSON cannot hold, are written as null.
  // Strings are escaped; invalid UTF-8 bytes become U+FFFD.
  std::string dump(int indent = 2) const;

 private:
  void dump_to(std::string& out, int indent, int depth) const;
  bool is_container() const { return kind_ == Kind::array || kind_ == Kind::object; }

  Kind kind_ = Kind::null;
  bool bool_ = false;
  std::int64_t int_ = 0;
  double number_ = 0.0;
  std::string string_;
  std::vector<Json> items_;
  std::vector<std::pair<std::string, Json>> members_;
};

// `text` as a quoted JSON string literal.
std::string json_quote(std::string_view text);

// hostname, os (uname: sysname release machine), cpu_model (/proc/cpuinfo),
// cpu_cores (hardware threads), compiler (__VERSION__). Missing items read "unknown".
std::map<std::string, std::string> machine_info();

// The git revision the library was built from ("-dirty" appended when tracked
// files had changes; "unknown" outside git); defined in a file written at every
// build (cmake/git_revision.cmake).
std::string git_revision();

}  // namespace wl
