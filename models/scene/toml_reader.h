// A small typed reader over toml++ tables for scene files (internal to
// models/scene; include only from .cpp files of this folder). It records the
// dotted key path and source line of every value, quotes values as written in
// the file, and reports every key it was never asked for as unknown, so that a
// typo can never fall back to a default.
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/scene/toml_include.h"

#include "models/scene/format_number.h"
#include "models/scene/scene.h"

namespace wl::scene_detail {

// The scene text and its name, for error messages.
class Source {
 public:
  Source(std::string_view text, std::string file);
  const std::string& file() const { return file_; }
  // The node's text exactly as written (shortened when very long).
  std::string written(const toml::node& n) const;
  // One line of the file, trimmed (empty when out of range).
  std::string line_text(int line) const;
  [[noreturn]] void fail(int line, std::string key, std::string value, std::string expected) const;

 private:
  std::vector<std::string> lines_;
  std::string file_;
};

int line_of(const toml::node& n);

// Reads one table. Every read_* call declares its key as known, whether or not
// it is present; finish() rejects any other key of the table.
class TableReader {
 public:
  TableReader(const Source& src, const toml::table& table, std::string path);

  const Source& source() const { return src_; }
  const toml::table& table() const { return table_; }
  int line() const { return line_of(table_); }
  // "cloth.radius_m" for key "radius_m" of [cloth]; the key alone at the root.
  std::string key_path(std::string_view key) const;
  // The table's own name, e.g. "[cloth]", or "the top level".
  std::string describe() const;

  // Declares `key` as known and returns its node (nullptr when absent).
  const toml::node* get(std::string_view key);

  // Typed reads: absent → false and `out` unchanged; present and valid → true.
  // Wrong type or failed predicate → SceneError with `expected`.
  bool read_number(std::string_view key, double& out, const std::string& expected,
                   const std::function<bool(double)>& ok = {});
  bool read_number(std::string_view key, std::optional<double>& out, const std::string& expected,
                   const std::function<bool(double)>& ok = {});
  bool read_int(std::string_view key, int& out, const std::string& expected,
                const std::function<bool(long long)>& ok = {});
  bool read_bool(std::string_view key, bool& out);
  bool read_string(std::string_view key, std::string& out, const std::string& expected,
                   const std::function<bool(const std::string&)>& ok = {});
  // One of `names`; returns its index through `out`.
  bool read_choice(std::string_view key, int& out, const std::vector<std::string>& names);
  // An array of finite numbers (integers accepted) for which `ok` holds.
  bool read_number_array(std::string_view key, std::vector<double>& out, const std::string& expected,
                         const std::function<bool(const std::vector<double>&)>& ok = {});
  bool read_vec3(std::string_view key, std::array<double, 3>& out, const std::string& expected);
  bool read_string_array(std::string_view key, std::vector<std::string>& out, const std::string& expected);

  std::optional<TableReader> subtable(std::string_view key);
  // [[key]] arrays of tables; entry paths are "key[0]", "key[1]", ...
  std::vector<TableReader> table_array(std::string_view key);

  // Declares every key of this table as known (for tables whose keys are names).
  void accept_all_keys();
  // Throws for the first (by line) key that was never declared. `note` is
  // appended to the list of known keys in the message.
  void finish(const std::string& note = "") const;

  [[noreturn]] void fail_at(const toml::node& n, std::string_view key, const std::string& expected) const;
  [[noreturn]] void fail_missing(std::string_view key, const std::string& expected) const;
  // Fails at `key` when it is present, else at the table's line quoting the default.
  [[noreturn]] void fail_key(std::string_view key, const std::string& expected, const std::string& default_value) const;
  // Declares keys as known without reading them.
  void declare(const std::vector<std::string>& keys);

 private:
  const Source& src_;
  const toml::table& table_;
  std::string path_;
  std::vector<std::string> known_;
};

}  // namespace wl::scene_detail
