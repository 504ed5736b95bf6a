// The commands the README and docs/cli.md show are accepted by the program: each names a
// subcommand that exists, only flags its --help lists, a value from the listed choices
// where a flag has them, and scene files that exist.
#include <gtest/gtest.h>

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

// Lines of fenced code blocks that start with `build/sluice ` or `sluice `, with their
// `\` continuations joined.
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
      const std::string t = line.substr(first);
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

}  // namespace
}  // namespace sluice
