// The reference trajectory and its cache (driver/reference_cache.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "driver/experiment_meta.h"
#include "driver/reference_cache.h"
#include "tests/driver/driver_test_data.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

using test::random_trajectory;
using test::ScratchDir;
using test::tiny_scene_text;

TEST(ReferenceCache, HashDependsOnSceneTextModelAndOverrides) {
  ReferenceOptions o;
  const std::string text = tiny_scene_text();
  const std::string h = text_hash(reference_key(text, "yarn", {}, o));
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, text_hash(reference_key(text, "yarn", {}, o)));
  EXPECT_NE(h, text_hash(reference_key(tiny_scene_text(0.006), "yarn", {}, o)));
  EXPECT_NE(h, text_hash(reference_key(text + "# a comment\n", "yarn", {}, o)));
  EXPECT_NE(h, text_hash(reference_key(text, "fem", {}, o)));
  EXPECT_NE(h, text_hash(reference_key(text, "yarn", {{"duration_s", "0.002"}}, o)));
}

TEST(ReferenceCache, FileRoundTripsAndRejectsOtherKeysAndTornFiles) {
  ScratchDir dir;
  Reference r;
  r.trajectory = random_trajectory(9, 3, 5);
  r.rtol = 1e-10;
  r.atol = 1e-13;
  r.cpu_s = 1.5;
  const auto file = dir / "ref.bin";
  write_reference_file(file, "key A", r);
  Reference back;
  ASSERT_TRUE(read_reference_file(file, "key A", back));
  EXPECT_EQ(back.trajectory.times, r.trajectory.times);
  EXPECT_EQ(back.trajectory.positions, r.trajectory.positions);
  EXPECT_EQ(back.rtol, 1e-10);
  EXPECT_EQ(back.cpu_s, 1.5);
  EXPECT_FALSE(read_reference_file(file, "key B", back));
  EXPECT_FALSE(read_reference_file(dir / "missing.bin", "key A", back));
  const std::string bytes = test::read_text(file);
  std::ofstream(dir / "torn.bin", std::ios::binary) << bytes.substr(0, bytes.size() - 8);
  EXPECT_FALSE(read_reference_file(dir / "torn.bin", "key A", back));
}

TEST(ReferenceCache, SecondCallReadsTheFileAndAChangedSceneComputesAnew) {
  ScratchDir dir;
  const std::string text = tiny_scene_text(0.002);
  const Scene scene = parse_scene(text, "tiny.toml");
  ReferenceOptions o;
  o.cache_dir = dir / "reference";
  o.rtols = {1e-7};  // tolerance irrelevant here; keeps the test fast
  o.required_rtol = 1e-7;
  o.progress = false;
  const Reference first = load_or_compute_reference(scene, text, "fem", {}, o);
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(std::filesystem::exists(first.file));
  EXPECT_EQ(first.file, o.cache_dir / (first.hash + ".bin"));
  EXPECT_EQ(first.rtol, 1e-7);
  ASSERT_EQ(first.attempts.size(), 1u);
  const Reference second = load_or_compute_reference(scene, text, "fem", {}, o);
  EXPECT_TRUE(second.from_cache);
  EXPECT_TRUE(second.attempts.empty());
  EXPECT_EQ(second.trajectory.positions, first.trajectory.positions);
  EXPECT_EQ(second.rtol, first.rtol);

  // A file of the right key and times whose trajectory is not this scene's: computed anew.
  const std::string key = reference_key(text, "fem", {}, o);
  Reference fewer_points = first;
  fewer_points.trajectory.positions = first.trajectory.positions.topRows(first.trajectory.positions.rows() - 3);
  Reference not_finite = first;
  not_finite.trajectory.positions(4, 0) = std::nan("");
  for (const Reference& tampered : {fewer_points, not_finite}) {
    write_reference_file(first.file, key, tampered);
    const Reference again = load_or_compute_reference(scene, text, "fem", {}, o);
    EXPECT_FALSE(again.from_cache);
    EXPECT_EQ(again.trajectory.positions, first.trajectory.positions);
  }

  const std::string other_text = text + "# changed\n";
  const Reference third = load_or_compute_reference(parse_scene(other_text, "tiny.toml"), other_text, "fem", {}, o);
  EXPECT_FALSE(third.from_cache);
  EXPECT_NE(third.hash, first.hash);
  EXPECT_EQ(test::count_entries(o.cache_dir), 2);
}

TEST(ReferenceCache, NoConvergingToleranceIsAnError) {
  ScratchDir dir;
  const std::string text = tiny_scene_text(0.002);
  ReferenceOptions o;
  o.cache_dir = dir / "reference";
  o.max_steps = 3;  // far too few for 2 ms: every attempt ends with max_steps
  o.rtols = {1e-9, 1e-8};
  o.progress = false;
  try {
    load_or_compute_reference(parse_scene(text, "tiny.toml"), text, "fem", {}, o);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("rtol=1e-09"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rtol=1e-08: max_steps"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(o.cache_dir) && test::count_entries(o.cache_dir) > 0);
}

}  // namespace
}  // namespace wl
