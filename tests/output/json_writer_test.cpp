#include "output/json_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "output/atomic_file.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

// Python states the expected values itself and compares with what json.load reads.
const char* kCheckScript = R"PY(
import json, sys
d = json.load(open(sys.argv[1], encoding="utf-8"))
want = {
    "plain": "cloth",
    "quotes": 'say "hi" \\ back/slash',
    "controls": "a\nb\tc\rd\x01e\x1ff\x7f\b\f",
    "unicode": "\u03bc = 0.5 \u2013 \u20ac \U0001F600",
    "invalid_utf8": "a\ufffdb",
    "numbers": [0.1, 1/3, 1e-300, 1.7976931348623157e308, -2.5, 0.0],
    "integers": [0, -7, 9007199254740993, 9223372036854775807],
    "nonfinite": [None, None],
    "flags": [True, False, None],
    "nested": {"empty_object": {}, "empty_array": [], "list": [{"a": 1}, [2, 3]]},
    "key \"with\" quotes\n": 1,
}
if d != want:
    for k in want:
        if d.get(k) != want[k]:
            print(f"{k!r}: got {d.get(k)!r}, want {want[k]!r}")
    sys.exit(1)
if list(d) != list(want):
    sys.exit(f"key order {list(d)}")
print("OK")
)PY";

Json tricky_document() {
  Json doc = Json::object();
  doc.set("plain", "cloth");
  doc.set("quotes", "say \"hi\" \\ back/slash");
  doc.set("controls", std::string("a\nb\tc\rd\x01"
                                  "e\x1f"
                                  "f\x7f\b\f"));
  doc.set("unicode", "\u03bc = 0.5 \u2013 \u20ac \U0001F600");
  doc.set("invalid_utf8", std::string("a\xff"
                                      "b"));
  doc.set("numbers", std::vector<double>{0.1, 1.0 / 3.0, 1e-300, std::numeric_limits<double>::max(), -2.5, 0.0});
  doc.set("integers",
          Json::array().push(0).push(-7).push(9007199254740993LL).push(std::numeric_limits<std::int64_t>::max()));
  doc.set("nonfinite", Json::array().push(std::nan("")).push(HUGE_VAL));
  doc.set("flags", Json::array().push(true).push(false).push(nullptr));
  Json& nested = doc["nested"];
  nested["empty_object"] = Json::object();
  nested["empty_array"] = Json::array();
  nested["list"].push(Json::object().set("a", 1)).push(Json::array().push(2).push(3));
  doc.set("key \"with\" quotes\n", 1);
  return doc;
}

TEST(JsonWriter, EscapingAndNumbersRoundTripThroughPython) {
  ASSERT_TRUE(test::python_with("json"));
  test::ScratchDir dir;
  const auto file = dir / "summary.json";
  write_file_atomically(file, tricky_document().dump());
  const auto r = test::run_command(std::string(test::python()) + " -c " + test::shell_quote(kCheckScript) + " " +
                                   test::shell_quote(file.string()));
  EXPECT_EQ(r.exit_code, 0) << r.output << "\n" << tricky_document().dump();
  EXPECT_NE(r.output.find("OK"), std::string::npos) << r.output;
}

TEST(JsonWriter, PrettyPrintsWithIndentation) {
  Json doc = Json::object();
  doc.set("scene", "drape").set("gravity", std::vector<double>{0, 0, -9.81});
  doc["stats"]["steps"] = 12;
  EXPECT_EQ(doc.dump(),
            "{\n"
            "  \"scene\": \"drape\",\n"
            "  \"gravity\": [0, 0, -9.81],\n"
            "  \"stats\": {\n"
            "    \"steps\": 12\n"
            "  }\n"
            "}\n");
}

TEST(JsonWriter, SetReplacesInPlaceAndMisuseThrows) {
  Json doc = Json::object();
  doc.set("a", 1).set("b", 2).set("a", 3);
  EXPECT_EQ(doc.size(), 2u);
  EXPECT_EQ(doc.dump(0), "{\n\"a\": 3,\n\"b\": 2\n}\n");
  Json s = "text";
  EXPECT_THROW(s.push(1), std::logic_error);
  EXPECT_THROW(s["k"], std::logic_error);
}

TEST(MachineInfo, HasEveryKeyFilled) {
  const auto info = machine_info();
  for (const char* key : {"hostname", "os", "cpu_model", "cpu_cores", "compiler"}) {
    ASSERT_TRUE(info.count(key)) << key;
    EXPECT_FALSE(info.at(key).empty()) << key;
  }
  EXPECT_NE(info.at("os").find("Linux"), std::string::npos) << info.at("os");
  EXPECT_GT(std::stoi(info.at("cpu_cores")), 0);
}

// The revision written at build time names a commit of this checkout (twelve hex
// digits, "-dirty" when tracked files had changes), not "unknown"; outside git it is "unknown".
TEST(GitRevision, NamesACommitOfTheCheckout) {
  const std::string git = std::string("git -C '") + WEAVELAB_SOURCE_DIR + "' ";
  if (std::system((git + "rev-parse --git-dir >/dev/null 2>&1").c_str()) != 0) {
    EXPECT_EQ(git_revision(), "unknown");
    return;
  }
  std::string revision = git_revision();
  const std::string dirty = "-dirty";
  if (revision.size() > dirty.size() && revision.compare(revision.size() - dirty.size(), dirty.size(), dirty) == 0)
    revision.resize(revision.size() - dirty.size());
  ASSERT_EQ(revision.size(), 12u) << git_revision();
  EXPECT_EQ(revision.find_first_not_of("0123456789abcdef"), std::string::npos) << git_revision();
  EXPECT_EQ(std::system((git + "cat-file -e " + revision + "^{commit} 2>/dev/null").c_str()), 0) << git_revision();
}

}  // namespace
}  // namespace wl
