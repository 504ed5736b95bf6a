// `sluice bench --end-to-end`: a whole render timed and split, as a table and a CSV.
// (Suite named Render*: it carries the CTest label render, which the sanitizer run of
// .ci/run leaves out with what else runs the renderer.) BenchCli: the modes' flags and
// output directories, without the renderer.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test_process.h"

namespace sluice {
namespace {

using test::CaseDir;

using test::kTinyScene;

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string item; std::getline(ss, item, sep);) out.push_back(item);
  return out;
}

TEST(RenderBenchEndToEnd, SplitsARenderIntoItsParts) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const test::Result r = test::run_sluice(dir, {"bench", "--end-to-end", "tiny.json", "--duration", "0.1", "--fps",
                                                "20", "--resolution", "64x64", "-o", "out"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("simul_s"), std::string::npos) << r.out;
  const auto t = nlohmann::json::parse(test::read_text(dir.work() / "out" / "timing.json"));
  EXPECT_EQ(t.at("frames").get<long>(), 3);  // t = 0, 0.05, 0.1
  double parts = 0;
  for (const char* key : {"simulation_s", "drawing_s", "png_wait_s", "exports_s", "video_s"}) {
    EXPECT_GE(t.at(key).get<double>(), 0.0) << key;
    parts += t.at(key).get<double>();
  }
  EXPECT_GT(t.at("simulation_s").get<double>(), 0.0);
  EXPECT_GT(t.at("video_s").get<double>(), 0.0);
  EXPECT_LE(parts, t.at("total_s").get<double>());
  EXPECT_TRUE(test::fs::exists(dir.work() / "out" / "tiny.mp4"));

  const std::vector<std::string> lines = split(test::read_text(dir.work() / "out" / "end_to_end.csv"), '\n');
  ASSERT_EQ(lines.size(), 2u);
  const std::vector<std::string> head = split(lines[0], ','), row = split(lines[1], ',');
  ASSERT_EQ(head.size(), row.size());
  EXPECT_EQ(head[0], "scene");
  EXPECT_EQ(row[0], "tiny");
  EXPECT_EQ(row[1], "64x64");
  EXPECT_EQ(row[4], "3");
}

TEST(RenderBenchEndToEnd, TakesOneScene) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const test::Result r = test::run_sluice(dir, {"bench", "--end-to-end", "tiny.json", "tiny.json", "-o", "out"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--end-to-end takes one scene"), std::string::npos) << r.err;
}

// An earlier render in -o DIR (frames, summary) stays unless --overwrite is given, as for
// `render` (exit 3); refused before anything runs, so no EGL is needed here.
TEST(BenchCli, EndToEndRefusesAnEarlierRunWithoutOverwrite) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  test::write_text(dir.work() / "out/frames/frame_00000.png", "earlier frame");
  test::write_text(dir.work() / "out/summary.json", R"({"status": "completed"})");
  const test::Result r = test::run_sluice(
      dir, {"bench", "--end-to-end", "tiny.json", "--duration", "0.1", "--resolution", "64x64", "-o", "out"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("sluice: output error: out: output directory holds a previous run (summary.json, frames/); "
                       "pass --overwrite to replace it"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(test::read_text(dir.work() / "out/frames/frame_00000.png"), "earlier frame");
  // An earlier bench's table alone is refused too.
  test::fs::remove_all(dir.work() / "out");
  test::write_text(dir.work() / "out/end_to_end.csv", "earlier");
  const test::Result csv = test::run_sluice(dir, {"bench", "--end-to-end", "tiny.json", "-o", "out"});
  EXPECT_EQ(csv.status, 3) << csv.err;
  EXPECT_NE(csv.err.find("out: output directory holds a previous run (end_to_end.csv)"), std::string::npos) << csv.err;
  EXPECT_EQ(test::read_text(dir.work() / "out/end_to_end.csv"), "earlier");
}

TEST(RenderBenchEndToEnd, OverwriteReplacesAnEarlierRun) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  test::write_text(dir.work() / "out/frames/frame_00009.png", "earlier frame");
  const test::Result r = test::run_sluice(dir, {"bench", "--end-to-end", "tiny.json", "--duration", "0.1", "--fps",
                                                "20", "--resolution", "64x64", "-o", "out", "--overwrite"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(test::fs::exists(dir.work() / "out/frames/frame_00009.png"));
  EXPECT_TRUE(test::fs::exists(dir.work() / "out/end_to_end.csv"));
}

// A sweep's bench.csv is replaced only with --overwrite; the refusal comes before any run.
TEST(BenchCli, SweepRefusesAnEarlierBenchCsvWithoutOverwrite) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const std::vector<std::string> sweep = {"bench", "tiny.json", "--sweep", "solver.tolerance=0.1", "-o", "out"};
  ASSERT_EQ(test::run_sluice(dir, sweep).status, 0);
  const std::string first = test::read_text(dir.work() / "out/bench.csv");
  const test::Result again = test::run_sluice(dir, sweep);
  EXPECT_EQ(again.status, 3) << again.err;
  EXPECT_NE(again.err.find("sluice: output error: out: output directory holds a previous run (bench.csv, bench.md"),
            std::string::npos)
      << again.err;
  EXPECT_NE(again.err.find("pass --overwrite to replace it"), std::string::npos) << again.err;
  EXPECT_EQ(again.out.find("sweep of"), std::string::npos) << "nothing runs: " << again.out;
  EXPECT_EQ(test::read_text(dir.work() / "out/bench.csv"), first);
  std::vector<std::string> overwrite = sweep;
  overwrite.push_back("--overwrite");
  const test::Result replaced = test::run_sluice(dir, overwrite);
  EXPECT_EQ(replaced.status, 0) << replaced.err;
  // --collect into a directory with a table: the same rule.
  const test::Result collect = test::run_sluice(dir, {"bench", "--collect", "out", "-o", "out"});
  EXPECT_EQ(collect.status, 3) << collect.err;
}

// The command lines of --jobs, run and collected, give a table whose `set` column says
// which values each run had (it was empty: each line passed them as --set).
TEST(BenchCli, JobsRunsKeepTheirSettingsThroughCollect) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const test::Result jobs = test::run_sluice(
      dir, {"bench", "tiny.json", "--sweep", "solver.tolerance=0.1,0.01", "--jobs", "jobs.txt", "-o", "sweep"});
  ASSERT_EQ(jobs.status, 0) << jobs.err;
  const std::string cmd = "cd '" + dir.work().string() + "' && OMP_NUM_THREADS=1 sh jobs.txt >jobs.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir.work() / "jobs.log");
  const test::Result collect =
      test::run_sluice(dir, {"bench", "--collect", "sweep/run_0001", "sweep/run_0002", "-o", "sweep"});
  ASSERT_EQ(collect.status, 0) << collect.err;
  const std::vector<std::string> lines = split(test::read_text(dir.work() / "sweep/bench.csv"), '\n');
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[1].find(",\"solver.tolerance=0.1\","), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(",\"solver.tolerance=0.01\","), std::string::npos) << lines[2];
}

// Values are split at top-level commas only: a JSON array is one value.
TEST(BenchCli, SweepValuesSplitOutsideBrackets) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const test::Result r = test::run_sluice(
      dir, {"bench", "tiny.json", "--sweep", "solver.gravity=[0,-9.81],[0,-5]", "--jobs", "jobs.txt", "-o", "s"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> lines = split(test::read_text(dir.work() / "jobs.txt"), '\n');
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("--sweep 'solver.gravity=[0,-9.81]'"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("--sweep 'solver.gravity=[0,-5]'"), std::string::npos) << lines[1];
  // A malformed --sweep is a flag mistake: exit 1, naming the flag.
  const test::Result bad = test::run_sluice(dir, {"bench", "tiny.json", "--sweep", "solver.tolerance", "-o", "s"});
  EXPECT_EQ(bad.status, 1) << bad.err;
  EXPECT_EQ(bad.err.rfind("sluice: error: --sweep solver.tolerance: ", 0), 0u) << bad.err;
}

// A flag that the chosen mode does not read is refused (it was silently ignored), and so
// is an odd --end-to-end resolution with a hint that names only bench's own flags.
TEST(BenchCli, FlagsTheModeDoesNotReadAreRefused) {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"tiny.json", "--sweep", "solver.tolerance=0.1", "--steps", "5", "-o", "s"},
       "--steps 5: bench --sweep does not read it"},
      {{"--end-to-end", "tiny.json", "--sweep", "solver.tolerance=0.1", "-o", "e"},
       "--sweep solver.tolerance=0.1: bench --end-to-end does not read it"},
      {{"tiny.json", "--collect", "s", "-o", "c"}, "SCENE tiny.json: bench --collect merges the bench.csv files"},
      {{"tiny.json", "--resolution", "64x64"}, "--resolution 64x64: bench SCENE... does not read it"},
      {{"--end-to-end", "tiny.json", "--resolution", "321x180", "-o", "e"},
       "--resolution 321x180: bench --end-to-end encodes H.264 (yuv420p), which needs even width and height, "
       "e.g. 322x180"},
  };
  for (const auto& [args, fragment] : cases) {
    SCOPED_TRACE(fragment);
    std::vector<std::string> full = {"bench"};
    full.insert(full.end(), args.begin(), args.end());
    const test::Result r = test::run_sluice(dir, full);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("sluice: error: " + fragment), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("--no-video"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("--format"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(test::fs::exists(dir.work() / "s"));
  EXPECT_FALSE(test::fs::exists(dir.work() / "e"));
  EXPECT_FALSE(test::fs::exists(dir.work() / "c"));
}

}  // namespace
}  // namespace sluice
