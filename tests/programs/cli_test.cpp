// `huygens run` as a user meets it when things go wrong (docs/robustness.md): every end is a
// message and a documented exit code, output targets are checked before the run, a failed write
// or a signal leaves meta.json listing exactly the complete dumps, and a scene too large for the
// memory is refused before anything is allocated. The program runs as a separate process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "scenes_dir.hpp"

namespace fs = std::filesystem;

namespace {

struct Result {
  int code = -1;  // exit code, or 128 + signal when killed by one
  std::string output;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path work_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("cli_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Runs `sh -c "PREFIX huygens ARGS"` in `dir`, stdout and stderr into one text.
Result run(const fs::path& dir, const std::string& args, const std::string& prefix = "") {
  const std::string out = (dir / "output.txt").string();
  const std::string cmd =
      "cd '" + dir.string() + "' && " + prefix + " '" + HUYGENS_CLI + "' " + args + " > '" + out + "' 2>&1";
  const int status = std::system(("sh -c \"" + cmd + "\"").c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.output = slurp(out);
  return r;
}

// A small Huygens scene (64^2, one Gaussian) with `water` as its water block.
fs::path scene(const fs::path& dir, const std::string& water = "{}", int n = 64) {
  const fs::path p = dir / "scene.json";
  std::ofstream(p) << R"({"solver": "huygens", "grid": {"n": )" << n << R"(, "length_m": 2.0, "margin": 8},
    "water": )" << water
                   << R"(, "time": {"dt_s": 0.01},
    "initial": [{"type": "gaussian", "x_m": 1.0, "y_m": 1.0, "sigma_m": 0.1, "amplitude_m": 0.01}]})";
  return p;
}

// The dumps meta.json lists, and the files in the folder besides meta.json and run.pvd.
void expect_listed_equals_present(const fs::path& dumps) {
  const auto meta = nlohmann::json::parse(slurp(dumps / "meta.json"));
  std::set<std::string> listed, present;
  for (const auto& d : meta["dumps"])
    for (const auto& f : d["files"]) listed.insert(f.get<std::string>());
  for (const auto& e : fs::directory_iterator(dumps))
    if (e.path().filename() != "meta.json" && e.path().filename() != "run.pvd")
      present.insert(e.path().filename().string());
  EXPECT_EQ(listed, present);
}

}  // namespace

TEST(Cli, NumbersOnTheCommandLineAreCheckedWithTheirRange) {
  const fs::path d = work_dir("numbers");
  scene(d);
  for (const char* bad : {"--steps 99999999999999999999", "--steps 9223372036854775808", "--steps -1", "--steps 1e3",
                          "--steps ''", "--dump-every 0", "--dump ''", "--stats-json ''", "--nosuch",
                          "--dump out --dump-format vtu", "--dump-format vtk"}) {
    const Result r = run(d, std::string("run scene.json ") + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_EQ(r.output.rfind("huygens: ", 0), 0u) << bad << ": " << r.output;
  }
}

TEST(Cli, OutputTargetsAreCheckedBeforeTheRun) {
  const fs::path d = work_dir("targets");
  scene(d);
  for (const char* bad : {"--stats-json missing/stats.json", "--stats-json .", "--dump scene.json"}) {
    const Result r = run(d, std::string("run scene.json --steps 5 ") + bad);
    EXPECT_EQ(r.code, 1) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("cannot write"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("steps to t"), std::string::npos) << "the run must not start: " << r.output;
  }
  EXPECT_FALSE(fs::exists(d / "missing"));
}

// --stats-json naming the scene or a file of the dump replaced it after the run, with exit code 0.
TEST(Cli, StatsJsonMustNotReplaceTheSceneOrADumpFile) {
  const fs::path d = work_dir("apart");
  scene(d);
  const std::string text = slurp(d / "scene.json");
  fs::create_directories(d / "out");
  for (const char* bad :
       {"--stats-json scene.json", "--stats-json ./scene.json", "--dump out --stats-json out/meta.json",
        "--dump out --stats-json out/../out/eta_000002.npy"}) {
    const Result r = run(d, std::string("run scene.json --steps 2 --fast-plans ") + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--stats-json"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("steps to t"), std::string::npos) << "the run must not start: " << r.output;
  }
  EXPECT_EQ(slurp(d / "scene.json"), text);
  EXPECT_TRUE(fs::is_empty(d / "out"));
  // beside the dumps under another name is fine
  EXPECT_EQ(run(d, "run scene.json --steps 2 --fast-plans --dump out --stats-json out/stats.json").code, 0);
  EXPECT_TRUE(fs::exists(d / "out" / "stats.json"));
}

TEST(Cli, ADumpFolderOfAnotherRunIsRefusedUnlessOverwrite) {
  const fs::path d = work_dir("reuse");
  scene(d);
  ASSERT_EQ(run(d, "run scene.json --steps 4 --dump out --fast-plans").code, 0);
  const Result again = run(d, "run scene.json --steps 2 --dump out --fast-plans");
  EXPECT_EQ(again.code, 2) << again.output;
  EXPECT_NE(again.output.find("--overwrite"), std::string::npos) << again.output;
  // only the run's own files are removed: not notes, not an input such as a bed kept beside the dumps
  const std::vector<std::string> mine = {"notes.txt", "bed.npy", "eta.npy", "eta_final.npy", "eta_12.npy"};
  for (const auto& name : mine) std::ofstream(d / "out" / name) << "mine";
  const Result over = run(d, "run scene.json --steps 2 --dump out --overwrite --fast-plans");
  EXPECT_EQ(over.code, 0) << over.output;
  for (const auto& name : mine) {
    EXPECT_EQ(slurp(d / "out" / name), "mine") << name;
    fs::remove(d / "out" / name);
  }
  expect_listed_equals_present(d / "out");
  EXPECT_EQ(nlohmann::json::parse(slurp(d / "out" / "meta.json"))["dumps"].size(), 3u);
}

// The VTK files (--dump-format both) are listed in meta.json and are the run's files: a second run
// is refused, --overwrite removes them with run.pvd.
TEST(Cli, VtkDumpsAreListedAndOverwrittenLikeTheNpy) {
  const fs::path d = work_dir("vtk");
  scene(d);
  ASSERT_EQ(run(d, "run scene.json --steps 4 --dump-every 2 --dump out --dump-format both --fast-plans").code, 0);
  for (const char* name : {"eta_000004.npy", "grid_000004.vti", "run.pvd"}) EXPECT_TRUE(fs::exists(d / "out" / name));
  expect_listed_equals_present(d / "out");
  EXPECT_EQ(nlohmann::json::parse(slurp(d / "out" / "meta.json"))["dump_format"], "both");
  EXPECT_EQ(run(d, "run scene.json --steps 2 --dump out --dump-format vtk --fast-plans").code, 2);
  ASSERT_EQ(run(d, "run scene.json --steps 2 --dump out --overwrite --fast-plans").code, 0);
  EXPECT_FALSE(fs::exists(d / "out" / "run.pvd"));
  expect_listed_equals_present(d / "out");  // no .vti left
}

// A full disk, made real by the file-size limit (ulimit -f, 1 KiB blocks): each dump (48^2
// visible floats) is 9 KiB, meta.json grows by ~200 bytes a dump and passes 64 KiB after a few
// hundred dumps: that write fails, and the meta.json before it must stay.
TEST(Cli, AFailedWriteStopsTheRunAndKeepsTheLastGoodMeta) {
  const fs::path d = work_dir("full");
  scene(d);
  const Result r = run(d, "run scene.json --steps 3000 --dump out --fast-plans", "ulimit -f 64;");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("cannot write out/meta.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("too large"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stage"), std::string::npos) << "the stage table is printed: " << r.output;
  expect_listed_equals_present(d / "out");  // no temporary, no unlisted step
  EXPECT_GT(nlohmann::json::parse(slurp(d / "out" / "meta.json"))["dumps"].size(), 100u);
}

TEST(Cli, SigintStopsTheRunCleanly) {
  const fs::path d = work_dir("sigint");
  scene(d, "{}", 256);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ASSERT_EQ(chdir(d.c_str()), 0);
    const int fd = ::open("output.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(HUYGENS_CLI, HUYGENS_CLI, "run", "scene.json", "--steps", "100000000", "--dump", "out", "--dump-every", "3",
          "--fast-plans", static_cast<char*>(nullptr));
    _exit(127);
  }
  // wait for a few dumps, then interrupt
  for (int i = 0; i < 600; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (fs::exists(d / "out" / "eta_000006.npy")) break;
  }
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const std::string out = slurp(d / "output.txt");
  EXPECT_NE(out.find("by SIGINT"), std::string::npos) << out;
  EXPECT_NE(out.find("stage"), std::string::npos) << out;
  const auto meta = nlohmann::json::parse(slurp(d / "out" / "meta.json"));
  EXPECT_EQ(meta["stopped"]["signal"], "SIGINT");
  EXPECT_GE(meta["stopped"]["step"].get<long long>(), 6);
  EXPECT_FALSE(meta["complete"].get<bool>());
  expect_listed_equals_present(d / "out");
}

TEST(Cli, AScenePastTheMemoryIsRefusedBeforeTheRun) {
  const fs::path d = work_dir("memory");
  scene(d, "{}", 1024);  // about 30 MiB of fields
  const Result r = run(d, "run scene.json --steps 1 --fast-plans", "HUYGENS_MAX_MEMORY_GIB=0.01");
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("needs"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("available"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("$.grid.n"), std::string::npos) << r.output;
  const Result ok = run(d, "run scene.json --steps 1 --fast-plans", "HUYGENS_MAX_MEMORY_GIB=1");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_NE(ok.output.find("estimated"), std::string::npos) << ok.output;
  for (const char* bad : {"abc", "-1", "nan", "1x"}) {  // a malformed cap is bad input, not a lack of memory
    const Result r = run(d, "run scene.json --steps 1 --fast-plans", std::string("HUYGENS_MAX_MEMORY_GIB=") + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("HUYGENS_MAX_MEMORY_GIB"), std::string::npos) << r.output;
  }
}

// Many ships: the memory refusal names the part that dominates and its key ($.ships, not the
// grid), and a fleet whose waves would cost more than 16 grid transforms a step is refused at
// $.ships with the bound, before anything is allocated.
TEST(Cli, ManyShipsAreRefusedAtTheShipsKey) {
  const fs::path d = work_dir("ships");
  const nlohmann::json kelvin = nlohmann::json::parse(slurp(fs::path(huygens::test::scenes_dir()) / "kelvin.json"));
  auto fleet = [&](int count) {  // kelvin's ship, `count` times, on parallel paths
    nlohmann::json s = kelvin;
    s["ships"] = nlohmann::json::array();
    for (int i = 0; i < count; ++i) {
      nlohmann::json ship = kelvin["ships"][0];
      for (auto& p : ship["path"]) p["y_m"] = 5.0 + 40.0 * i / count;
      s["ships"].push_back(ship);
    }
    std::ofstream(d / "scene.json") << s.dump();
  };
  fleet(400);  // 400 patches of 96^2: about 57 MiB of ship patches, the largest part
  const Result r = run(d, "run scene.json --steps 1 --fast-plans", "HUYGENS_MAX_MEMORY_GIB=0.04");
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("the largest part, ship patches"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is set by $.ships"), std::string::npos) << r.output;
  fleet(456);  // 16 x 512^2 / 96^2 = 455 ships at most
  const Result many = run(d, "run scene.json --steps 1 --fast-plans");
  EXPECT_EQ(many.code, 2) << many.output;
  EXPECT_NE(many.output.find("$.ships: 456 ships"), std::string::npos) << many.output;
  EXPECT_NE(many.output.find("at most 455 ships"), std::string::npos) << many.output;
}

TEST(Cli, TheAddressSpaceLimitCountsAsMemory) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space and doubles the resident memory";
#endif
  const fs::path d = work_dir("ulimit");
  scene(d, "{}", 4096);  // about 0.6 GiB of fields
  const Result r = run(d, "run scene.json --steps 1 --fast-plans", "ulimit -v 400000;");
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("needs"), std::string::npos) << r.output;
}

TEST(Cli, DegenerateWaterIsRefusedWithItsPath) {
  const fs::path d = work_dir("degenerate");
  const std::pair<const char*, const char*> cases[] = {
      {R"({"depth_m": 1e-100})", "$.water.depth_m"},
      {R"({"gravity_mps2": 1e-300, "surface_tension_npm": 0})", "$.water.gravity_mps2"},
      {R"({"gravity_mps2": 0, "surface_tension_npm": 1e-300})", "$.water.surface_tension_npm"},
  };
  for (const auto& [water, path] : cases) {
    scene(d, water);
    const Result r = run(d, "run scene.json --steps 2 --fast-plans");
    EXPECT_EQ(r.code, 2) << water << ": " << r.output;
    EXPECT_NE(r.output.find(path), std::string::npos) << water << ": " << r.output;
  }
}

#ifdef HUYGENS_VIZ
TEST(Cli, TheViewersCommandLineIsCheckedToo) {
  const fs::path d = work_dir("viz");
  for (const char* bad : {"--frames abc", "--frames 0", "--time nan", "--time -1", "--size 10x10x", "--subsample 99",
                          "--screenshot ''", "a.json b.json", "."}) {
    const std::string out = (d / "output.txt").string();
    const int status = std::system(("'" + std::string(HUYGENS_VIZ) + "' " + bad + " > '" + out + "' 2>&1").c_str());
    ASSERT_TRUE(WIFEXITED(status)) << bad;
    EXPECT_EQ(WEXITSTATUS(status), 2) << bad << ": " << slurp(out);
    EXPECT_EQ(slurp(out).rfind("huygens-viz: ", 0), 0u) << bad << ": " << slurp(out);
  }
  // the screenshot must not replace the scene it renders (it did, with exit code 0)
  const fs::path sc = scene(d);
  const std::string text = slurp(sc);
  const std::string out = (d / "output.txt").string();
  const int status = std::system(("'" + std::string(HUYGENS_VIZ) + "' '" + sc.string() + "' --headless --screenshot '" +
                                  sc.string() + "' > '" + out + "' 2>&1")
                                     .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2) << slurp(out);
  EXPECT_EQ(slurp(sc), text);
}
#endif

// An SPH scene's OBJ mesh is found beside the scene file wherever the program runs: the shipped
// sph_wedge.json named by path from another folder runs; a copy of the scene without its mesh
// beside it is a scene error naming the JSON path, exit 2 (not a mesh from the working folder).
// The viewer's built-in copy (by name, from a folder without meshes/) reads the mesh compiled in.
TEST(Cli, AMeshObstacleIsReadBesideItsSceneFromAnyFolder) {
  const fs::path d = work_dir("mesh");
  const fs::path shipped = fs::absolute(fs::path(huygens::test::scenes_dir()) / "sph_wedge.json");
  ASSERT_TRUE(fs::exists(shipped)) << shipped;
  const Result ok = run(d, "run '" + shipped.string() + "' --steps 1");
  EXPECT_EQ(ok.code, 0) << ok.output;
  fs::create_directories(d / "copy");
  fs::copy_file(shipped, d / "copy" / "sph_wedge.json");
  fs::create_directories(d / "meshes");  // a mesh in the working folder must not be taken
  fs::copy_file(shipped.parent_path() / "meshes" / "wedge.obj", d / "meshes" / "wedge.obj");
  const Result missing = run(d, "run copy/sph_wedge.json --steps 1");
  EXPECT_EQ(missing.code, 2) << missing.output;
  EXPECT_NE(missing.output.find("$.sph.obstacles[0].file"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("copy/meshes/wedge.obj"), std::string::npos) << missing.output;
#ifdef HUYGENS_VIZ
  fs::remove_all(d / "meshes");
  const std::string out = (d / "viz.txt").string();
  const int status =
      std::system(("cd '" + d.string() + "' && '" + std::string(HUYGENS_VIZ) +
                   "' sph_wedge --headless --frames 1 --size 64x64 --screenshot w.png > '" + out + "' 2>&1")
                      .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << slurp(out);
  EXPECT_TRUE(fs::exists(d / "w.png")) << slurp(out);
#endif
}

// A shipped scene runs by its name from any folder (it is compiled in, with its meshes); a file of
// that name in the working folder comes first; an unknown name is refused listing the shipped ones.
TEST(Cli, AShippedSceneRunsByNameAndAFileOfThatNameComesFirst) {
  const fs::path d = work_dir("shipped");
  const Result wedge = run(d, "run sph_wedge --steps 1");
  EXPECT_EQ(wedge.code, 0) << wedge.output;
  EXPECT_NE(wedge.output.find("solver sph"), std::string::npos) << wedge.output;
  const Result dry = run(d, "run ocean.json --dry-run");
  EXPECT_EQ(dry.code, 0) << dry.output;
  EXPECT_NE(dry.output.find("solver huygens"), std::string::npos) << dry.output;
  const Result shipped = run(d, "run ocean --steps 1");
  EXPECT_EQ(shipped.code, 0) << shipped.output;
  EXPECT_NE(shipped.output.find("wind sea"), std::string::npos) << shipped.output;
  fs::copy_file(scene(d), d / "ocean.json");  // a 64^2 Huygens scene under the shipped scene's name
  const Result local = run(d, "run ocean.json --steps 1");
  EXPECT_EQ(local.code, 0) << local.output;
  EXPECT_EQ(local.output.find("wind sea"), std::string::npos) << local.output;  // the shipped ocean has one
  const Result unknown = run(d, "run oceanic --steps 1");
  EXPECT_EQ(unknown.code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("no shipped scene of that name"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("sph_wedge.json"), std::string::npos) << unknown.output;
  const Result path = run(d, "run no/ocean.json --steps 1");  // a path is a path: no fallback
  EXPECT_EQ(path.code, 2) << path.output;
  EXPECT_NE(path.output.find("cannot open scene file no/ocean.json"), std::string::npos) << path.output;
}

// OpenMP threads spin briefly (GOMP_SPINCOUNT 3000) then sleep, unless the user sets
// OMP_WAIT_POLICY or GOMP_SPINCOUNT (program.cpp): libgomp prints what it took with OMP_DISPLAY_ENV.
TEST(Cli, OpenMpWaitsSpinBrieflyUnlessTheUserChooses) {
  const fs::path d = work_dir("omp");
  scene(d);
  const std::string args = "run scene.json --steps 1 --fast-plans";
  const Result unset = run(d, args, "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose");
  EXPECT_NE(unset.output.find("GOMP_SPINCOUNT = '3000'"), std::string::npos) << unset.output;
  const Result active = run(d, args, "env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose");
  EXPECT_NE(active.output.find("OMP_WAIT_POLICY = 'ACTIVE'"), std::string::npos) << active.output;
  EXPECT_EQ(active.output.find("GOMP_SPINCOUNT = '3000'"), std::string::npos) << active.output;
  const Result mine = run(d, args, "env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=77 OMP_DISPLAY_ENV=verbose");
  EXPECT_NE(mine.output.find("GOMP_SPINCOUNT = '77'"), std::string::npos) << mine.output;
}

// ---- the memory estimate against the run's peak resident memory ----
namespace {

// Peak RSS (unit: MiB) of `huygens run SCENE --steps 1 --fast-plans`, and the estimate it printed.
std::pair<double, double> peak_and_estimate(const fs::path& dir, const fs::path& scene_file) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open((dir / "output.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    execl(HUYGENS_CLI, HUYGENS_CLI, "run", scene_file.c_str(), "--steps", "1", "--fast-plans",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage use{};
  EXPECT_EQ(wait4(pid, &status, 0, &use), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << slurp(dir / "output.txt");
  const std::string out = slurp(dir / "output.txt");
  const auto at = out.find("memory ");
  double estimate = -1;
  if (at != std::string::npos) {
    estimate = std::stod(out.substr(at + 7));
    if (out.compare(out.find(' ', at + 7) + 1, 3, "GiB") == 0) estimate *= 1024;
  }
  return {use.ru_maxrss / 1024.0, estimate};
}

nlohmann::json shipped(const std::string& name) {
  return nlohmann::json::parse(slurp(fs::path(huygens::test::scenes_dir()) / name));
}

}  // namespace

// Sizes where the fields dominate: the estimate (made from the parsed sizes before allocating)
// must be within -15 % / +25 % of the peak RSS growth over a 64^2 run (the program, libraries and
// thread stacks). It may err high (a refusal a little early), not much low (an OOM kill).
TEST(Cli, TheMemoryEstimateMatchesThePeakOfTheRun) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space and doubles the resident memory";
#endif
  const fs::path d = work_dir("estimate");
  const double base = peak_and_estimate(d, scene(d)).first;
  auto big_default = shipped("default.json");
  big_default["grid"]["n"] = 2048;
  auto big_ocean = shipped("ocean.json");
  big_ocean["grid"]["n"] = 1024;
  auto big_channel = shipped("channel.json");
  big_channel["lbm"]["grid"] = {{"cols", 3200}, {"rows", 1600}, {"cell_m", 0.001}};
  big_channel["lbm"]["time"] = {{"dt_s", 0.0003}};
  auto big_pool = shipped("pool.json");
  big_pool["sph"]["spacing_m"] = 0.0025;
  for (const auto& [name, json] : {std::pair{"default", big_default}, std::pair{"ocean", big_ocean},
                                   std::pair{"channel", big_channel}, std::pair{"pool", big_pool}}) {
    const fs::path f = d / (std::string(name) + ".json");
    std::ofstream(f) << json.dump();
    const auto [peak, estimate] = peak_and_estimate(d, f);
    const double growth = peak - base;
    EXPECT_GT(estimate, 0) << name;
    EXPECT_GE(estimate, 0.85 * growth) << name << ": estimate " << estimate << " MiB, growth " << growth << " MiB";
    EXPECT_LE(estimate, 1.25 * growth) << name << ": estimate " << estimate << " MiB, growth " << growth << " MiB";
  }
}
