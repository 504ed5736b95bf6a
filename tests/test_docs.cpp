// The commands the README and docs/cli.md show are accepted by the program: each names a
// subcommand that exists, only flags its --help lists, a value from the listed choices
// where a flag has them, and scene files that exist.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <regex>
#include <set>

#include "test_process.h"

namespace sluice {
namespace {

using test::CaseDir;
using test::run_sluice;

const std::string kRoot = std::string(SLUICE_SOURCE_DIR) + "/";

struct Command {
  std::string file;
  std::string text;
  std::vector<std::string> words;
};

std::vector<std::string> split_words(const std::string& s) {
  std::vector<std::string> w;
  std::istringstream in(s);
  for (std::string t; in >> t;) {
    if (t.front() == '#') break;  // a shell comment
    w.push_back(t);
  }
  return w;
}

// Lines of fenced code blocks that start with `build/sluice ` or `sluice ` (or run it
// after `&& `, as the README's first command does), with their `\` continuations joined.
std::vector<Command> commands_in(const std::string& file) {
  std::istringstream in(test::read_text(kRoot + file));
  std::vector<Command> out;
  bool fenced = false;
  std::string pending;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("```")) {
      fenced = !fenced;
      continue;
    }
    if (!fenced) continue;
    if (!pending.empty()) {
      pending += " " + line;
    } else {
      const auto first = line.find_first_not_of(' ');
      if (first == std::string::npos) continue;
      std::string t = line.substr(first);
      if (const auto chained = t.find("&& build/sluice "); chained != std::string::npos) t = t.substr(chained + 3);
      if (!t.starts_with("build/sluice ") && !t.starts_with("sluice ")) continue;
      pending = t;
    }
    if (!pending.empty() && pending.back() == '\\') {
      pending.pop_back();
      continue;
    }
    Command c{file, pending, split_words(pending)};
    c.words.erase(c.words.begin());  // the program
    out.push_back(c);
    pending.clear();
  }
  return out;
}

std::string help_of(const std::vector<std::string>& path) {
  CaseDir dir;
  std::vector<std::string> args = path;
  args.push_back("--help");
  const auto r = run_sluice(dir, args);
  return r.status == 0 ? r.out : std::string();
}

// The names listed under "Subcommands:" in a help text.
std::set<std::string> subcommands_in(const std::string& help) {
  std::set<std::string> names;
  const auto at = help.find("Subcommands:");
  if (at == std::string::npos) return names;
  std::istringstream in(help.substr(at));
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != ' ') break;
    std::istringstream w(line);
    std::string name;
    if (w >> name) names.insert(name);
  }
  return names;
}

// The help line of a flag ("  --color-by TEXT:{cfl,speed} ..."), or "" if not listed.
std::string help_line_of(const std::string& help, const std::string& flag) {
  std::istringstream in(help);
  const std::regex name("(^|[ ,])" + std::regex_replace(flag, std::regex("[-]"), "\\-") + "([ ,=]|$)");
  for (std::string line; std::getline(in, line);) {
    const auto first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] != '-') continue;
    if (std::regex_search(line.substr(first, line.find("  ", first) - first), name)) return line;
  }
  return {};
}

// "{a,b,c}" of a help line, empty when the flag has no fixed choices.
std::set<std::string> choices_in(const std::string& help_line) {
  std::set<std::string> out;
  const auto a = help_line.find('{'), b = help_line.find('}');
  if (a == std::string::npos || b == std::string::npos || b < a) return out;
  std::istringstream in(help_line.substr(a + 1, b - a - 1));
  for (std::string v; std::getline(in, v, ',');) out.insert(v);
  return out;
}

bool is_placeholder(const std::string& v) {
  return v.find_first_of("[]|.") != std::string::npos || std::all_of(v.begin(), v.end(), [](char ch) {
           return std::isupper(static_cast<unsigned char>(ch)) || ch == '_' ||
                  std::isdigit(static_cast<unsigned char>(ch));
         });
}

std::vector<std::string> problems_of(const Command& c, const std::set<std::string>& top) {
  std::vector<std::string> bad;
  if (c.words.empty() || !top.count(c.words[0])) return {"unknown subcommand in: " + c.text};
  std::vector<std::string> path{c.words[0]};
  std::string help = help_of(path);
  std::size_t k = 1;
  if (const auto subs = subcommands_in(help); k < c.words.size() && subs.count(c.words[k])) {
    path.push_back(c.words[k++]);
    help = help_of(path);
  }
  if (help.empty()) return {"no help for '" + path.back() + "' in: " + c.text};
  for (; k < c.words.size(); ++k) {
    std::string w = c.words[k];
    if (w.starts_with("[")) w = w.substr(1);  // a synopsis' optional part: "[--fps"
    if (w.starts_with("scenes/") && w.ends_with(".json") && !std::filesystem::exists(kRoot + w))
      bad.push_back("no such scene file " + w + " in: " + c.text);
    if (!w.starts_with("-") || w == "-" || w.size() < 2) continue;
    const std::string flag = w.substr(0, w.find_first_of("=],"));
    if (flag.find_first_not_of("-") == std::string::npos) continue;
    const std::string line = help_line_of(help, flag);
    if (line.empty()) {
      bad.push_back("flag " + flag + " is not an option of '" + path.back() + "' in: " + c.text);
      continue;
    }
    const auto choices = choices_in(line);
    if (choices.empty() || k + 1 >= c.words.size()) continue;
    const std::string v = c.words[k + 1];
    if (v.starts_with("-") || is_placeholder(v)) continue;
    // A list option ("{csv,vtk} ...") takes comma-separated choices: --export csv,vtk.
    const bool list = line.find("} ...") != std::string::npos;
    std::istringstream parts(v);
    for (std::string part; std::getline(parts, part, list ? ',' : '\0');)
      if (!choices.count(part))
        bad.push_back("value " + v + " of " + flag + " is not one of its choices in: " + c.text);
  }
  return bad;
}

TEST(Docs, CommandsShownAreAccepted) {
  const std::set<std::string> top = subcommands_in(help_of({}));
  ASSERT_TRUE(top.count("render") && top.count("compare")) << "no subcommands found in sluice --help";
  std::size_t checked = 0;
  for (const char* file : {"README.md", "docs/cli.md"}) {
    const auto cmds = commands_in(file);
    EXPECT_GE(cmds.size(), 5u) << file << ": the check found almost no commands";
    for (const Command& c : cmds) {
      for (const std::string& p : problems_of(c, top)) ADD_FAILURE() << c.file << ": " << p;
      ++checked;
    }
  }
  std::printf("[ measured ] %zu documented commands checked\n", checked);
}

// The check itself rejects what it must: an unknown flag, an unknown subcommand, a value
// outside a flag's choices and a missing scene file.
TEST(Docs, CheckRejectsWhatTheProgramWould) {
  const std::set<std::string> top = subcommands_in(help_of({}));
  auto problems = [&](const std::string& text) {
    Command c{"x", text, split_words(text)};
    c.words.erase(c.words.begin());
    return problems_of(c, top).size();
  };
  EXPECT_EQ(problems("sluice render scenes/dam_break.json --color-by speed"), 0u);
  EXPECT_EQ(problems("sluice figures series a.csv --y iterations -o f.png"), 0u);
  EXPECT_EQ(problems("sluice render scenes/dam_break.json --no-such-flag"), 1u);
  EXPECT_EQ(problems("sluice rendr scenes/dam_break.json"), 1u);
  EXPECT_EQ(problems("sluice render scenes/dam_break.json --color-by sped"), 1u);
  EXPECT_EQ(problems("sluice render scenes/no_such_scene.json"), 1u);
  EXPECT_EQ(problems("sluice figures series a.csv --pareto-front"), 1u);
  EXPECT_EQ(problems("sluice simulate scenes/dam_break.json --export csv,vtk"), 0u);
  EXPECT_EQ(problems("sluice simulate scenes/dam_break.json --export csv,pdf"), 1u);
  EXPECT_EQ(problems("sluice render scenes/dam_break.json --color-by speed,cfl"), 1u);
}

// --- the README's commands, run ------------------------------------------------------

// The words of a command as a shell passes them: "..." and '...' hold spaces, and a word
// starting with # ends the command.
std::vector<std::string> shell_words(const std::string& s) {
  std::vector<std::string> w;
  std::string cur;
  bool in_word = false;
  char quote = 0;
  for (char ch : s) {
    if (quote) {
      if (ch == quote)
        quote = 0;
      else
        cur += ch;
    } else if (ch == '"' || ch == '\'') {
      quote = ch;
      in_word = true;
    } else if (ch == ' ' || ch == '\t') {
      if (in_word) w.push_back(cur);
      cur.clear();
      in_word = false;
    } else if (ch == '#' && !in_word) {
      break;
    } else {
      cur += ch;
      in_word = true;
    }
  }
  if (in_word) w.push_back(cur);
  return w;
}

// A README command and the arguments appended to it to make it short: a coarser spacing,
// a shorter duration, a smaller frame. They change how long it runs, not which code runs.
struct Shortened {
  std::string shown;  // as the README shows it, without "build/sluice " and comments
  std::vector<std::string> extra;
  // A validation's verdict on a shortened run (exit 1: a row outside bounds meant for its
  // full length) is no failure here; a scene, flag or output error or an instability is.
  bool verdict_may_fail = false;
};

// The README's commands that make the program render (EGL: suite Render*), in its order.
const std::vector<Shortened> kReadmeRendering = {
    {"render scenes/dam_break.json", {"--duration", "0.1", "--set", "spacing=0.04"}},
    {"render scenes/first_scene.json", {"--duration", "0.1"}},
    {"still scenes/first_scene.json --time 1.2 -o first.png", {"--set", "spacing=0.04"}},
    {"render scenes/rotor.json --color-by speed --resolution 1920x1080",
     {"--duration", "0.05", "--set", "spacing=0.03"}},
    {"still scenes/dam_break.json --time 0.8 --color-by pressure -o fig.png", {"--set", "spacing=0.04"}},
    {"montage scenes/hydrostatic.json --times 0.5,3 --color-by pressure --vary "
     "solver.boundary_pressure=solved,extrapolation --title \"Boundary pressure\" -o grid.png",
     {"--set", "spacing=0.04"}},
    {"render scenes/paddle.json --export csv,vtk", {"--duration", "0.05", "--set", "spacing=0.04"}},
    {"bench --end-to-end", {"--duration", "0.05", "--fps", "20", "--resolution", "320x180", "--set", "spacing=0.02"}},
    // The run of the first command above.
    {"figures run renders/dam_break", {}},
    {"still scenes/dam_break.json --time 0.5 -o actual.png", {"--set", "spacing=0.04"}},
    // The golden image is the one just made (the README keeps it in the repository).
    {"compare golden.png actual.png --preset tests --region 0,0,1280,32 --diff diff.png", {}},
};

// The README's other commands, in its order.
const std::vector<Shortened> kReadmeOthers = {
    {"simulate scenes/paddle.json --export vtk", {"--duration", "0.05", "--set", "spacing=0.04"}},
    {"bench scenes/dam_break.json --steps 300", {"--set", "spacing=0.04"}},
    {"bench scenes/dam_break.json --duration 1 --sweep time.dt=2.5e-4,5e-4,1e-3", {"--set", "spacing=0.04"}},
    {"validate hydrostatic", {"--set", "spacing=0.02", "time.settle=0.1", "time.duration=0.6"}, true},
    {"suite --short", {"--case", "jet"}},
};

// The README's commands as run here: "build/sluice " and comments dropped, words joined.
std::vector<std::string> readme_commands() {
  std::vector<std::string> out;
  for (const Command& c : commands_in("README.md")) {
    std::vector<std::string> w = shell_words(c.text);
    w.erase(w.begin());
    std::string text;
    for (const auto& x : w) text += (text.empty() ? "" : " ") + (x.find(' ') != std::string::npos ? '"' + x + '"' : x);
    out.push_back(text);
  }
  return out;
}

// Runs `commands` in one case folder that holds the shipped scenes (as the README's
// commands, run from the repository root, see them); each must exit 0.
void run_readme_commands(const std::vector<Shortened>& commands) {
  const std::vector<std::string> shown = readme_commands();
  CaseDir dir;
  std::filesystem::create_directory_symlink(kRoot + "scenes", dir.work() / "scenes");
  for (const Shortened& c : commands) {
    EXPECT_NE(std::find(shown.begin(), shown.end(), c.shown), shown.end())
        << "not a command of README.md (update the list in tests/test_docs.cpp): " << c.shown;
    if (c.shown.starts_with("compare golden.png"))
      std::filesystem::copy_file(dir.work() / "actual.png", dir.work() / "golden.png");
    std::vector<std::string> args = shell_words(c.shown);
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const auto t0 = std::chrono::steady_clock::now();
    const test::Result r = run_sluice(dir, args);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ measured ] %5.1f s  %s\n", s, c.shown.c_str());
    if (c.verdict_may_fail && r.status == 1 && r.out.find("FAILED") != std::string::npos) continue;
    EXPECT_EQ(r.status, 0) << c.shown << "\n" << r.err << r.out.substr(r.out.size() > 2000 ? r.out.size() - 2000 : 0);
  }
}

// Every command the README shows is run by one of the two tests below.
TEST(Docs, EveryReadmeCommandIsRun) {
  const std::vector<std::string> shown = readme_commands();
  EXPECT_GE(shown.size(), 15u) << "the check found almost no commands in README.md";
  for (const std::string& c : shown) {
    auto listed = [&](const std::vector<Shortened>& list) {
      return std::any_of(list.begin(), list.end(), [&](const Shortened& x) { return x.shown == c; });
    };
    EXPECT_TRUE(listed(kReadmeRendering) || listed(kReadmeOthers))
        << "README.md shows a command no test runs (add it to a list in tests/test_docs.cpp): " << c;
  }
}

// The README's commands that do not render, shortened; each exits 0 (or gives its
// verdict, for the validation).
TEST(Docs, ReadmeCommandsRun) { run_readme_commands(kReadmeOthers); }

// The README's commands that render, shortened; each exits 0.
TEST(RenderDocs, ReadmeCommandsRun) { run_readme_commands(kReadmeRendering); }

}  // namespace
}  // namespace sluice
