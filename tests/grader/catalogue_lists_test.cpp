// The catalogue is the one list of causes (tools/grader/diagnoses.json, issue 37): no cause id is
// written as a string in the grader's C++ (it names causes by the generated cause::k...
// constants), and the mistake models and the catalogue's entries answer to each other: every
// model the grader replays is an entry naming that model, and every entry naming a model has one.
// Both read the grader's sources as the build globs them (tools/grader/CMakeLists.txt: every .h
// and .cpp under tools/grader), and the test's own tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/cause_ids.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = CLOTHREF_SOURCE_DIR;

// The contents of every ordinary string literal of C++ `source`, with the line each starts on;
// comments, raw strings (R"x(...)x", JSON written in a test) and character literals are skipped.
std::vector<std::pair<int, std::string>> stringLiterals(const std::string& source) {
  std::vector<std::pair<int, std::string>> literals;
  int line = 1;
  const std::size_t n = source.size();
  const auto identifier = [&](std::size_t k) {
    return k < n && (std::isalnum(static_cast<unsigned char>(source[k])) || source[k] == '_');
  };
  for (std::size_t i = 0; i < n; ++i) {
    const char c = source[i];
    if (c == '\n') {
      ++line;
    } else if (source.compare(i, 2, "//") == 0) {
      while (i + 1 < n && source[i + 1] != '\n') ++i;
    } else if (source.compare(i, 2, "/*") == 0) {
      const std::size_t end = std::min(source.find("*/", i + 2), n);
      line += int(std::count(source.begin() + long(i), source.begin() + long(end), '\n'));
      i = std::min(end + 1, n);
    } else if (c == 'R' && i + 1 < n && source[i + 1] == '"' && (i == 0 || !identifier(i - 1))) {
      const std::size_t open = source.find('(', i);
      const std::string close = ")" + source.substr(i + 2, open - i - 2) + "\"";
      const std::size_t end = std::min(source.find(close, open), n);
      line += int(std::count(source.begin() + long(i), source.begin() + long(end), '\n'));
      i = std::min(end + close.size() - 1, n);
    } else if (c == '\'' && i + 2 < n && (i == 0 || !identifier(i - 1))) {
      i += source[i + 1] == '\\' ? 3 : 2;  // 'x' or '\x' (a digit separator follows a digit)
    } else if (c == '"') {
      std::string text;
      for (++i; i < n && source[i] != '"'; ++i) {
        if (source[i] == '\\') text += source[i++];
        text += source[i];
      }
      literals.push_back({line, text});
    }
  }
  return literals;
}

TEST(StringLiterals, FindsALiteralInCodeOnly) {
  const auto found = stringLiterals(
      "f('\"'); // \"crashed\"\n/* \"unknown\"\n*/ R\"x(\"unstable\")x\";\n"
      "t.addCause(\"backup-alias\"); int k = 1'000;\n");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0], (std::pair<int, std::string>{4, "backup-alias"}));
}

// Every .h and .cpp under `tree` (relative to the source root), as paths from the root.
std::vector<std::string> sourcesUnder(const std::string& tree) {
  std::vector<std::string> paths;
  for (const auto& entry : fs::recursive_directory_iterator(kRoot / tree)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp"))
      paths.push_back(fs::relative(entry.path(), kRoot).string());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Every cause id written as a string literal in the grader (tools/grader) and its tests
// (tests/grader): "file:line id". Not counted: the students' and the course's files (submissions,
// the reference, the stand-in headers: graded inputs), this test and catalogue_test.cpp (which
// checks the generator against ids written out), tests/grader/run/ (its words are what a whole
// grade prints), and a line naming a verdict: verdict words (results.h, verdictTable()) are a
// vocabulary of their own, some equal to cause ids.
std::vector<std::pair<std::string, std::string>> rawCauseIds(int& files) {
  std::set<std::string> ids;
  for (const cause::NamedId& named : cause::namedIds()) ids.insert(named.id);
  std::vector<std::pair<std::string, std::string>> found;  // "file:line", id
  files = 0;
  for (const char* tree : {"tools/grader", "tests/grader"})
    for (const std::string& path : sourcesUnder(tree)) {
      bool skipped = false;
      for (const char* part :
           {"tools/grader/course/", "tools/grader/reference/", "tests/grader/submissions/",
            "tests/grader/corpus/", "tests/grader/handwritten/", "tests/grader/blind/",
            "tests/grader/adversarial/", "tests/grader/run/", "tests/grader/catalogue_test.cpp",
            "tests/grader/catalogue_lists_test.cpp"})
        skipped = skipped || startsWith(path, part);
      if (skipped) continue;
      ++files;
      const std::string source = test::readText(kRoot / path);
      std::vector<std::string> lines = {""};
      for (char c : source) c == '\n' ? lines.push_back("") : void(lines.back() += c);
      for (const auto& [line, text] : stringLiterals(source)) {
        if (!ids.count(text)) continue;
        const std::string& where = lines.at(std::size_t(line - 1));
        if (where.find("Verdict::") != std::string::npos ||
            where.find("verdict") != std::string::npos)
          continue;
        found.push_back({path + ":" + std::to_string(line), text});
      }
    }
  return found;
}

// A cause id written as a string is a list kept by hand, and a typo that builds: the grader
// names a cause by its constant (cause::kBackupAlias), generated from the catalogue.
TEST(CatalogueIds, NoCauseIdIsWrittenAsAStringInTheGraderOrItsTests) {
  int files = 0;
  for (const auto& [where, id] : rawCauseIds(files)) {
    ADD_FAILURE() << where << ": \"" << id << "\" written as a string; write cause::k... of "
                  << "grader/grade/cause_ids.h";
  }
  EXPECT_GT(files, 150);  // the walk found the grader
}

// The cause constants a model's code names (cause::kX -> its id), by `pattern`'s first group.
std::set<std::string> namedBy(const std::string& file, const std::string& pattern) {
  std::map<std::string, std::string> ids;  // constant name -> id
  for (const cause::NamedId& named : cause::namedIds()) ids[named.name] = named.id;
  const std::string source = test::readText(kRoot / file);
  std::set<std::string> found;
  const std::regex re(pattern);
  for (auto it = std::sregex_iterator(source.begin(), source.end(), re);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    EXPECT_TRUE(ids.count(name)) << file << ": cause::" << name << " is no constant";
    if (ids.count(name)) found.insert(ids.at(name));
  }
  EXPECT_FALSE(found.empty()) << file << ": no match of " << pattern;
  return found;
}

// The files of mistakes/ that hold a table of the integrator step's rows (integrate_step.h: the
// lines every method shares and one file per method family), found as the build finds sources.
std::vector<std::string> integratorTables() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(kRoot / "tools/grader/grade/mistakes")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("integrate_", 0) == 0 && entry.path().extension() == ".cpp" &&
        test::readText(entry.path()).find("std::vector<Row<") != std::string::npos)
      files.push_back("tools/grader/grade/mistakes/" + name);
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The catalogue's ids whose model is `model`.
std::set<std::string> entriesOf(const std::string& model) {
  std::set<std::string> ids;
  for (const cause::Entry& entry : cause::entries())
    if (entry.model == model) ids.insert(entry.id);
  return ids;
}

std::string joined(const std::set<std::string>& ids) {
  std::string out;
  for (const std::string& id : ids) out += (out.empty() ? "" : ", ") + id;
  return out;
}

// The models the grader replays (explain/replay.h), read from their code, and the catalogue's
// entries naming them are the same ids: a model without an entry, or an entry naming a model
// that does not answer to it, fails. A model's code is the table it is:
//   "integrator step"  the rows {cause::kY, methods, ...} of the step's tables (mistakes/
//                      integrate_step.cpp and the family files beside it: integrate_euler.cpp,
//                      ...) and probes/integrate/models.cpp's fitted models (one branch per id);
//   "force variant"    the rows {cause::kY, kProbed|kReplayed, ...} of the spring force's table
//                      in mistakes/formula_variants.cpp (forceRows(), the probe's);
//   "contact variant"  the rows {cause::kY, kBoth|kCloth|kSpheres, ...} of the contact's table
//                      in mistakes/formula_variants.cpp (contactRows()), and probes/collide.cpp's
//                      fitted constants and candidates of ContactModel;
//   "spring set"       probes/springs.cpp, the causes the fitted spring set stands for;
//   "spring fit"       explain/spring_fit.cpp, the constants the fit reads (k_s, k_d): the
//                      causes it names that are no force variant.
TEST(CatalogueModels, EveryModelHasAnEntryAndEveryEntryItsModel) {
  const std::string grade = "tools/grader/grade/";
  std::map<std::string, std::set<std::string>> models = {
      {"integrator step",
       [&] {
         std::set<std::string> ids;
         for (const std::string& file : integratorTables())
           for (const std::string& id : namedBy(file, R"(\{cause::(k\w+), k[EIMRA])"))
             ids.insert(id);
         for (const std::string& id :
              namedBy(grade + "probes/integrate/models.cpp", R"(\bid == cause::(k\w+))"))
           ids.insert(id);
         return ids;
       }()},
      {"force variant",
       [&] {
         return namedBy(grade + "mistakes/formula_variants.cpp",
                        R"(\{cause::(k\w+), k(Probed|Replayed)\b)");
       }()},
      {"contact variant",
       [&] {
         std::set<std::string> ids = namedBy(grade + "mistakes/formula_variants.cpp",
                                             R"(\{cause::(k\w+), k(Both|Cloth|Spheres)\b)");
         for (const char* more :
              {R"(candidates\.push_back\(\{\{cause::(k\w+)\})", R"(f\.cause == cause::(k\w+))"})
           for (const std::string& id : namedBy(grade + "probes/collide.cpp", more)) ids.insert(id);
         return ids;
       }()},
      {"spring set",
       [&] {
         std::set<std::string> ids =
             namedBy(grade + "probes/springs.cpp", R"(ids\.push_back\(cause::(k\w+)\))");
         for (const std::string& id :
              namedBy(grade + "probes/springs.cpp", R"(cause\.id == cause::(k\w+))"))
           ids.insert(id);
         return ids;
       }()},
      {"spring fit", {}}};
  // The spring fit names what it reads; a fitted constant is its own model, a fitted switch is
  // the force variant's.
  models.at("spring fit") = namedBy(grade + "explain/spring_fit.cpp", R"(cause::(k\w+))");
  for (const std::string& id : models.at("force variant")) models.at("spring fit").erase(id);
  std::set<std::string> modelled;
  for (const auto& [model, ids] : models) {
    SCOPED_TRACE(model);
    EXPECT_EQ(joined(entriesOf(model)), joined(ids))
        << "left: the catalogue's entries naming \"" << model << "\"; right: the ids its code "
        << "answers to";
    modelled.insert(model);
  }
  // Every model an entry names is one of these (a name the test does not know is no model).
  for (const cause::Entry& entry : cause::entries())
    if (*entry.model) {
      EXPECT_TRUE(modelled.count(entry.model)) << entry.id << ": " << entry.model;
    }
}

// The switches of struct `name` in `source` (`name = false`, `true`, `{}` or a number, comments
// left out), each expected to be set by a row somewhere in `source` (`.name = `); returns how
// many there are.
int expectEachSetByARow(const std::string& source, const std::string& name) {
  const std::size_t open = source.find("\nstruct " + name + " {");
  EXPECT_NE(open, std::string::npos) << "struct " << name;
  if (open == std::string::npos) return 0;
  const std::string body = std::regex_replace(source.substr(open, source.find("\n};", open) - open),
                                              std::regex("//[^\n]*"), "");
  int switches = 0;
  const std::regex field(R"(\b(\w+) = (false|true|\{\}|-?\d+))");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), field);
       it != std::sregex_iterator(); ++it) {
    const std::string value = (*it)[1];
    ++switches;
    EXPECT_NE(source.find("." + value + " = "), std::string::npos)
        << name << "::" << value << " is set by no row";
  }
  return switches;
}

// Every switch of the force and contact models (the structs of switches in
// mistakes/formula_variants.cpp: the formulas' and their loops') is set by a row of its table
// (`.name = `), so no switch is code that no mistake reaches.
TEST(CatalogueModels, EverySwitchOfAFormulaVariantIsSetByARow) {
  const std::string source =
      test::readText(kRoot / "tools/grader/grade/mistakes/formula_variants.cpp");
  for (const std::string name :
       {"SpringVariant", "ForceSwitches", "ContactVariant", "ContactSwitches"}) {
    SCOPED_TRACE(name);
    EXPECT_GT(expectEachSetByARow(source, name), 3);
  }
}

// Every switch of the integrator step (EveryMethod in mistakes/integrate_step.h, each family's
// struct of switches in its file) is set by a row of one of the step's tables (`.name = `), so
// no switch is code that no mistake reaches.
TEST(CatalogueModels, EverySwitchOfTheIntegratorStepIsSetByARow) {
  std::string source = test::readText(kRoot / "tools/grader/grade/mistakes/integrate_step.h");
  for (const std::string& file : integratorTables()) source += test::readText(kRoot / file);
  std::set<std::string> structs;
  const std::regex declared(R"(\nstruct (\w*(Switches|EveryMethod)) \{)");
  for (auto it = std::sregex_iterator(source.begin(), source.end(), declared);
       it != std::sregex_iterator(); ++it)
    structs.insert((*it)[1]);
  // every method's lines, explicit Euler, the predictor-corrector, RK4
  EXPECT_GE(structs.size(), 4u);
  for (const std::string& name : structs) {
    SCOPED_TRACE(name);
    EXPECT_GT(expectEachSetByARow(source, name), 0);
  }
}

}  // namespace
}  // namespace clothref::grader
