// Every repository path named in docs/ and README.md exists. A path is a word that starts with a
// top-level folder of the repository (lib/, tools/, tests/, docs/, golden/, cmake/, .github/,
// .ci/) or with a library area (core/, io/, ...: relative to lib/clothref/), or a markdown link
// target (relative to the document). Accepted forms: `{a,b}` alternatives (each must exist),
// `<name>` and `*` placeholders (at least one match), a trailing `:line`, and a name without its
// extension (`core/cloth` for cloth.h and cloth.cpp). Not checked: paths under build*/, the path
// after `-o`/`--out` (a command's output), and paths a document lists in a comment
// `<!-- not-in-repo: PATH... -->` (examples and generated files; a marked folder covers what is
// under it). And no document of the repository (every *.md below it, README.md and docs/ and the
// tests' and tools' own) cites a path of a machine (/work/, /home/, /root/, ...) or a file outside
// the repository (../shared, course-api.md): what the code relies on is written in docs/.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

// `a/{b,c}/d` -> a/b/d, a/c/d (innermost braces first, no nesting needed in practice).
std::vector<std::string> expandBraces(const std::string& path) {
  const std::size_t open = path.find('{');
  const std::size_t close = path.find('}', open);
  if (open == std::string::npos || close == std::string::npos) return {path};
  std::vector<std::string> out;
  std::stringstream alternatives(path.substr(open + 1, close - open - 1));
  for (std::string alternative; std::getline(alternatives, alternative, ',');)
    for (std::string& p : expandBraces(path.substr(0, open) + alternative + path.substr(close + 1)))
      out.push_back(std::move(p));
  return out;
}

// Whether one path component matches a pattern with `*` wildcards.
bool matchesComponent(const std::string& pattern, const std::string& name) {
  std::string regex;
  for (char c : pattern) {
    if (c == '*')
      regex += "[^/]*";
    else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')
      regex += c;
    else
      regex += std::string("\\") + c;
  }
  return std::regex_match(name, std::regex(regex));
}

// Whether `pattern` (relative to `base`, `*` within components) names at least one file or
// folder; the last component may also omit an extension.
bool exists(const fs::path& base, const std::string& pattern) {
  std::vector<fs::path> current{base};
  std::stringstream components(pattern);
  std::vector<std::string> parts;
  for (std::string part; std::getline(components, part, '/');)
    if (!part.empty() && part != ".") parts.push_back(part);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const bool last = k + 1 == parts.size();
    std::vector<fs::path> next;
    for (const fs::path& dir : current) {
      std::error_code error;
      if (!fs::is_directory(dir, error)) continue;
      for (const fs::directory_entry& entry : fs::directory_iterator(dir, error)) {
        const std::string name = entry.path().filename().string();
        const bool stem_match = last && matchesComponent(parts[k], entry.path().stem().string()) &&
                                entry.path().has_extension();
        if (matchesComponent(parts[k], name) || stem_match) next.push_back(entry.path());
      }
    }
    current = std::move(next);
    if (current.empty()) return false;
  }
  return true;
}

// Whether `path` is a marked path or lies under one.
bool isMarked(const std::set<std::string>& marked, const std::string& path) {
  for (const std::string& m : marked)
    if (path == m || path.rfind(m + "/", 0) == 0) return true;
  return false;
}

// The paths named in `document` (a file under `root`) that do not exist, as "LINE: PATH".
std::vector<std::string> missingPaths(const fs::path& root, const fs::path& document) {
  static const std::regex kPath(
      R"((^|[^\w./<>*{}-])((lib|tools|tests|docs|golden|cmake|\.github|\.ci|base|core|formula|fast|io|solver|scene|trace|diff|record|verify|analysis)/[\w./{},<>*+-]*[\w*>}]))");
  static const std::regex kLink(R"(\]\(([^)\s#]+)(#[^)]*)?\))");
  static const std::regex kOutput(R"((-o|--out|--output)\s+$)");
  static const std::regex kMarked(R"(<!--\s*not-in-repo:([^>]*)-->)");
  static const std::set<std::string> kAreas = {"base",   "formula", "core",    "fast", "io",
                                               "solver", "scene",   "trace",   "diff", "record",
                                               "golden", "verify",  "analysis"};
  std::ifstream in(document);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);

  std::set<std::string> marked;
  for (const std::string& line : lines)
    for (std::sregex_iterator m(line.begin(), line.end(), kMarked), end; m != end; ++m) {
      std::stringstream words((*m)[1].str());
      for (std::string word; words >> word;) {
        while (!word.empty() && (word.back() == '/' || word.back() == '.')) word.pop_back();
        marked.insert(word);
      }
    }

  std::vector<std::string> missing;
  for (std::size_t n = 0; n < lines.size(); ++n) {
    const std::string line = std::regex_replace(lines[n], kMarked, "");
    for (std::sregex_iterator m(line.begin(), line.end(), kPath), end; m != end; ++m) {
      std::string named = (*m)[2].str();
      while (!named.empty() && named.back() == '.') named.pop_back();
      const std::string before = line.substr(0, m->position(2));
      if (isMarked(marked, named) || std::regex_search(before, kOutput)) continue;
      const std::string first = named.substr(0, named.find('/'));
      for (std::string path : expandBraces(named)) {
        path = std::regex_replace(path, std::regex("<[^<>]*>"), "*");
        const bool found =
            exists(root, path) || (kAreas.count(first) && exists(root / "lib" / "clothref", path));
        if (!found) missing.push_back(std::to_string(n + 1) + ": " + path);
      }
    }
    for (std::sregex_iterator m(line.begin(), line.end(), kLink), end; m != end; ++m) {
      const std::string target = (*m)[1].str();
      if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
      if (isMarked(marked, target)) continue;
      if (!exists(document.parent_path(), target))
        missing.push_back(std::to_string(n + 1) + ": " + target);
    }
  }
  return missing;
}

std::vector<fs::path> documents(const fs::path& root) {
  std::vector<fs::path> out{root / "README.md"};
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root / "docs"))
    if (entry.path().extension() == ".md") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Every Markdown document of the repository: README.md, docs/, and the READMEs of tests/ and
// tools/ (build folders and hidden ones left out).
std::vector<fs::path> allDocuments(const fs::path& root) {
  std::vector<fs::path> out;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.rfind("build", 0) == 0 || name.rfind(".", 0) == 0)) {
      it.disable_recursion_pending();
      continue;
    }
    if (it->path().extension() == ".md") out.push_back(it->path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The lines of `document` that cite a machine's path or a file outside the repository, as
// "LINE: what".
std::vector<std::string> outsideCitations(const fs::path& document) {
  // an absolute path into a user's or a build machine's folders, wherever it starts a word
  static const std::regex kMachine(
      R"((^|[\s`'"(\[=:])(/(work|home|root|Users|mnt|srv)/[^\s`'")\]]*))");
  // the shared folder of the sessions that write the project, and the course's notes kept there
  static const std::regex kOutside(R"((\.\./shared|\bshared/product\.md|course-api(\.md)?))");
  std::ifstream in(document);
  std::vector<std::string> found;
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    std::smatch m;
    if (std::regex_search(line, m, kMachine))
      found.push_back(std::to_string(n) + ": " + m[2].str());
    else if (std::regex_search(line, m, kOutside))
      found.push_back(std::to_string(n) + ": " + m[1].str());
  }
  return found;
}

TEST(DocPaths, NoDocumentCitesAMachinePathOrAFileOutsideTheRepository) {
  const fs::path root = CLOTHREF_SOURCE_DIR;
  const std::vector<fs::path> docs = allDocuments(root);
  ASSERT_GE(docs.size(), 15u);  // README.md, docs/ and the tests' READMEs were found
  for (const fs::path& doc : docs)
    for (const std::string& cited : outsideCitations(doc))
      ADD_FAILURE() << fs::relative(doc, root).string() << ":" << cited
                    << ": cites a machine's path or a file outside the repository (say it in "
                       "docs/ in the project's own words)";
}

// The checker finds each kind of citation, and a scratch path of an example or a repository path
// is not one.
TEST(DocPaths, TheOutsideCheckerCatchesEachKindAndOnlyThose) {
  const test::TempDir dir;
  const fs::path doc = dir.path() / "page.md";
  test::writeText(doc,
                  "written from `/work/shared/notes.md`\n"
                  "see ../shared/product.md\n"
                  "the course's facts (course-api.md section 3)\n"
                  "a clone in /root/clothref there\n"
                  "(/home/ta/submissions)\n"
                  "cp -r golden /tmp/golden-old; tools/grader/course/ and docs/course.md\n"
                  "a network at work/ and a home/ folder, https://example.org/home/x\n");
  EXPECT_EQ(
      outsideCitations(doc),
      (std::vector<std::string>{"1: /work/shared/notes.md", "2: ../shared", "3: course-api.md",
                                "4: /root/clothref", "5: /home/ta/submissions"}));
}

TEST(DocPaths, EveryPathNamedInTheDocsExists) {
  const fs::path root = CLOTHREF_SOURCE_DIR;
  const std::vector<fs::path> docs = documents(root);
  ASSERT_GE(docs.size(), 10u);  // README.md and the docs/ pages were found
  for (const fs::path& doc : docs)
    for (const std::string& missing : missingPaths(root, doc))
      ADD_FAILURE() << fs::relative(doc, root).string() << ":" << missing
                    << " does not exist (mark an example or output with <!-- not-in-repo: "
                       "PATH -->)";
}

// The checker finds a missing path, and only that, among the forms it accepts.
TEST(DocPaths, TheCheckerCatchesAMissingPathAndOnlyThatOne) {
  const test::TempDir dir;
  const fs::path root = dir.path();
  fs::create_directories(root / "lib/clothref/core");
  fs::create_directories(root / "docs");
  test::writeText(root / "lib/clothref/core/cloth.h", "");
  test::writeText(root / "lib/clothref/core/cloth.cpp", "");
  test::writeText(root / "docs/other.md", "");
  const fs::path doc = root / "docs/page.md";
  test::writeText(doc,
                  "`lib/clothref/core/{cloth.h,cloth.cpp}` and core/cloth.cpp:12 and core/cloth\n"
                  "`lib/clothref/<area>/cloth.h`, see [other](other.md#part) and build/bin/x\n"
                  "clothref trace -o docs/out.jsonl; tests/generated/out.txt <!-- not-in-repo: "
                  "tests/generated -->\n"
                  "but `lib/clothref/core/{cloth.h,gone.h}` and [this](missing.md)\n");
  EXPECT_EQ(missingPaths(root, doc),
            (std::vector<std::string>{"4: lib/clothref/core/gone.h", "4: missing.md"}));
}

}  // namespace
}  // namespace clothref
