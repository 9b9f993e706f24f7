#include "grader/grade/explain/repair_proof.h"

#include <algorithm>
#include <functional>
#include <optional>
#include <regex>
#include <utility>

#include "grader/grade/cause_ids.h"
#include "grader/grade/submission/source_text.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace {

// `text` split into lines, each with its own line end ("\n", "\r\n" or none for the last).
std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end + 1 - start));
    start = end + 1;
  }
  return lines;
}

std::string trimmed(std::string line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  const std::size_t first = line.find_first_not_of(" \t");
  return first == std::string::npos ? "" : line.substr(first);
}

// One kind of pattern: where it is (on the blanked line) and how its line is repaired.
struct Pattern {
  std::string cause;
  std::regex found;                                    // on the blanked line
  std::function<std::string(const std::string&)> fix;  // the original line -> repaired
  std::string what;                                    // "stored as a vector (`.eval()`)"
};

bool isIntegrator(const std::string& stub) { return stub.find("::integrate") != std::string::npos; }

std::vector<Pattern> patternsOf(const std::string& stub) {
  std::vector<Pattern> patterns;
  // An `auto` holding an Eigen expression over the state (or over a vector a call returns, such
  // as normalized()): evaluated on its own line, into a plain vector.
  static const std::regex auto_expression(
      R"(\bauto\s*&{0,2}\s*\w+\s*=\s*[^;]*(position|velocity|acceleration|normalized)\s*\([^;]*[-+*/][^;]*;|\bauto\s*&{0,2}\s*\w+\s*=\s*[^;]*[-+*/][^;]*(position|velocity|acceleration|normalized)\s*\([^;]*;)");
  static const std::regex scalar_end(
      R"(\.\s*(norm|squaredNorm|stableNorm|sum|dot|value|eval)\s*\([^()]*\)\s*;)");
  patterns.push_back(
      {cause::kDanglingAutoExpression, auto_expression,
       [](const std::string& line) {
         static const std::regex declaration(R"(\bauto\s*&{0,2}\s*(\w+)\s*=\s*([^;]*);)");
         std::smatch m;
         if (!std::regex_search(line, m, declaration) || std::regex_search(m[0].str(), scalar_end))
           return line;
         return m.prefix().str() + "auto " + m[1].str() + " = (" + m[2].str() + ").eval();" +
                m.suffix().str();
       },
       "its `auto` expression stored as a vector with `.eval()`"});
  // A reference bound to the temporary std::max / std::min return (`const float& l =
  // std::max(a, b);`): it dangles at the end of the line; a copy does not.
  static const std::regex reference(R"((\bconst\s+[\w:]+\s*)&(\s*\w+\s*=\s*std::(max|min)\s*\())");
  patterns.push_back(
      {cause::kUndefinedBehaviour, reference,
       [](const std::string& line) { return std::regex_replace(line, reference, "$1$2"); },
       "its reference to the temporary std::max / std::min returns made a copy"});
  if (stub == "RungeKuttaFourth::integrate" || stub == "MidpointEuler::integrate") {
    // RK4's weights 1/6 and 1/3 (integer-division-rk4) and the halves of RK4's stages and the
    // midpoint's step (integer-division-half) are each 0 in int arithmetic.
    const bool rk4 = stub == "RungeKuttaFourth::integrate";
    const auto division = [&patterns](const std::string& cause, const std::string& denominators,
                                      const std::string& what) {
      const std::regex found(R"((^|[^.\w])1\s*/\s*)" + denominators + R"((?![.\w]))");
      patterns.push_back({cause, found,
                          [found](const std::string& line) {
                            return std::regex_replace(line, found, "$011.0f / $2");
                          },
                          what});
    };
    if (rk4)
      division(cause::kIntegerDivisionRk4, "([36])", "each `1 / 6` or `1 / 3` written `1.0f / n`");
    division(cause::kIntegerDivisionHalf, "(2)", "`1 / 2` written `1.0f / 2`");
  }
  if (isIntegrator(stub) && stub != "ExplicitEuler::integrate") {
    // A backup that is no copy: a vector of the Particles pointers, an Eigen::Ref view, or an
    // `auto` holding position() / velocity() of a body (an Eigen::Ref).
    static const std::regex pointers(
        R"(^(\s*)(auto\s*&?|std::vector\s*<\s*Particles\s*\*\s*>)\s*(\w+)\s*(=\s*particles\s*|\(\s*particles\s*\)|\{\s*particles\s*\})\s*;)");
    static const std::regex ref(R"(Eigen::Ref\s*<\s*(const\s+)?([\w:]+)\s*>)");
    static const std::regex view(
        R"(\bauto\s*&?\s*(\w+)\s*=\s*([\w\[\]]+\s*(->|\.)\s*(position|velocity)\s*\(\s*\))\s*;)");
    patterns.push_back(
        {cause::kBackupAlias,
         std::regex(
             R"((^\s*(auto\s*&?|std::vector\s*<\s*Particles\s*\*\s*>)\s*\w+\s*(=\s*particles\s*|\(\s*particles\s*\)|\{\s*particles\s*\})\s*;)|Eigen::Ref\s*<|\bauto\s*&?\s*\w+\s*=\s*[\w\[\]]+\s*(->|\.)\s*(position|velocity)\s*\(\s*\)\s*;)"),
         [](const std::string& line) {
           std::smatch m;
           if (std::regex_search(line, m, pointers)) {
             const std::string name = m[3].str(), copies = name + "_copies_";
             return m.prefix().str() + m[1].str() + "std::vector<Particles> " + copies +
                    "; for (auto* p_ : particles) " + copies +
                    ".push_back(*p_); std::vector<Particles*> " + name +
                    "; for (auto& c_ : " + copies + ") " + name + ".push_back(&c_);" +
                    m.suffix().str();
           }
           if (std::regex_search(line, m, view))
             return m.prefix().str() + "auto " + m[1].str() + " = " + m[2].str() + ".eval();" +
                    m.suffix().str();
           return std::regex_replace(line, ref, "$2");
         },
         "its backup made a copy of the state"});
    // The global deltaTime changed: restored when integrate() returns (a guard at the brace).
    patterns.push_back({cause::kDeltatimeMutated, std::regex(R"(\bdeltaTime\s*([-+*/]?=)(?!=))"),
                        nullptr, "deltaTime restored to its value when integrate() returns"});
  }
  if (stub == "Cloth::computeSpringForce")
    patterns.push_back(
        {cause::kDirectionNotNormalised, std::regex(R"(^\s*\w+\s*\.\s*normalized\s*\(\s*\)\s*;)"),
         [](const std::string& line) {
           static const std::regex discarded(R"((\w+)\s*\.\s*normalized\s*\(\s*\)\s*;)");
           return std::regex_replace(line, discarded, "$1.normalize();",
                                     std::regex_constants::format_first_only);
         },
         "`normalized();` written `normalize();`"});
  return patterns;
}

std::string lineList(const std::vector<SourceQuote>& lines) {
  std::string out = lines.size() == 1 ? "line " : "lines ";
  for (std::size_t k = 0; k < lines.size(); ++k)
    out += (k == 0 ? "" : k + 1 == lines.size() ? " and " : ", ") + std::to_string(lines[k].line);
  return out;
}

// The line of the brace that closes the block opened at the first '{' of line `from` or after
// (0-based lines of blanked code), and that opening line; {-1, -1} when there is none.
std::pair<int, int> blockOf(const std::vector<std::string>& blanked, int from) {
  int depth = 0, open = -1;
  for (int k = from; k < int(blanked.size()); ++k)
    for (const char c : blanked[std::size_t(k)]) {
      if (c == ';' && open < 0) return {-1, -1};  // a declaration, not a definition
      if (c == '{' && depth++ == 0 && open < 0) open = k;
      if (c == '}' && open >= 0 && --depth == 0) return {open, k};
    }
  return {-1, -1};
}

// A helper the stub calls that returns a reference to one of its own locals (`const
// Eigen::Vector4f& normal(...) { Eigen::Vector4f n = ...; return n; }`): the local is gone when
// the caller reads it (g++ even returns a null reference). Repaired: it returns by value (the
// reference dropped from its definition's and declarations' return type).
std::optional<Repair> localReferenceRepair(const std::string& file, const std::string& stub,
                                           const std::vector<std::string>& lines,
                                           const std::vector<std::string>& blanked,
                                           const StubLines& body) {
  std::string called;  // the stub's code, blanked
  for (int n = body.first; n <= body.last && n <= int(blanked.size()); ++n)
    called += blanked[std::size_t(n - 1)];
  static const std::regex head(R"(^\s*(static\s+|inline\s+)*[\w:<>, ]*[\w>]\s*&\s*(\w+)\s*\()");
  // `return n;`, or either branch of `return c ? n : v;`
  static const std::regex returned(R"(\breturn\s+([^;]*);)");
  static const std::regex alone(R"(^\s*(\w+)\s*$)");
  static const std::regex branches(R"(\?\s*(\w+)\s*:\s*(\w+)\s*$)");
  for (int k = 0; k < int(blanked.size()); ++k) {
    std::smatch m;
    if (body.contains(k + 1) || !std::regex_search(blanked[std::size_t(k)], m, head)) continue;
    const std::string name = m[2].str();
    if (!std::regex_search(called, std::regex("\\b" + name + R"(\s*\()"))) continue;
    const auto [open, close] = blockOf(blanked, k);
    if (open < 0) continue;
    std::string code;
    for (int j = open; j <= close; ++j) code += blanked[std::size_t(j)];
    // its own local (no static, reference or pointer), returned by name
    std::vector<std::string> names;
    for (auto r = std::sregex_iterator(code.begin(), code.end(), returned);
         r != std::sregex_iterator(); ++r) {
      const std::string value = (*r)[1].str();
      std::smatch m2;
      if (std::regex_search(value, m2, alone))
        names.push_back(m2[1].str());
      else if (std::regex_search(value, m2, branches))
        names.insert(names.end(), {m2[1].str(), m2[2].str()});
    }
    const auto ownLocal = [&](const std::string& local) {
      const std::regex declared(R"((^|[;{}(\s])([\w:]+(<[^;&*()]*>)?)\s+)" + local +
                                R"(\s*(=|;|\(|\{))");
      for (auto d = std::sregex_iterator(code.begin(), code.end(), declared);
           d != std::sregex_iterator(); ++d) {
        const std::string before = code.substr(0, std::size_t(d->position(0)));
        const std::string statement = before.substr(before.find_last_of(";{}") + 1);
        if ((*d)[2].str() != "return" && !std::regex_search(statement, std::regex(R"(\bstatic\b)")))
          return true;
      }
      return false;
    };
    const auto found = std::find_if(names.begin(), names.end(), ownLocal);
    if (found == names.end()) continue;
    const std::string local = *found;
    Repair repair{file, stub, cause::kUndefinedBehaviour, {}, {}, {}};
    // the definition and any declaration of the helper: the reference dropped
    const std::regex reference(R"(\s*&\s*()" + name + R"(\s*\())");
    std::vector<std::string> patched = lines;
    for (int j = 0; j < int(lines.size()); ++j) {
      const std::size_t at = std::size_t(j);
      if (body.contains(j + 1) || at >= blanked.size() || !std::regex_search(blanked[at], head) ||
          !std::regex_search(blanked[at], std::regex(R"(&\s*)" + name + R"(\s*\()")))
        continue;
      patched[at] =
          std::regex_replace(lines[at], reference, " $1", std::regex_constants::format_first_only);
      repair.lines.push_back({file, j + 1, trimmed(lines[at])});
    }
    if (repair.lines.empty()) continue;
    for (const std::string& line : patched) repair.patched += line;
    repair.what = lineList(repair.lines) + " repaired (`" + name + "` returns its local `" + local +
                  "` by value, not a reference to it, which is gone when it returns)";
    return repair;
  }
  return std::nullopt;
}

// A local of the stub declared without a value and first used in a compound assignment
// (`Eigen::Vector4f force; force += ...`): it starts from whatever the stack held. Repaired: it
// starts at zero (`Type::Zero()` for an Eigen type, 0 for a number).
// `one`: it starts at 1 instead (unsetStartProbe: whether the stub's numbers rest on that start).
std::optional<Repair> uninitialisedSumRepair(const std::string& file, const std::string& stub,
                                             const std::vector<std::string>& lines,
                                             const std::vector<std::string>& blanked,
                                             const StubLines& body, bool one = false) {
  static const std::regex declaration(
      R"(^(\s*)((const\s+)?(Eigen::\w+|float|double|int|long|unsigned|std::size_t|size_t))\s+(\w+)\s*;)");
  Repair repair{file, stub, cause::kUndefinedBehaviour, {}, {}, {}};
  std::vector<std::string> patched = lines;
  std::vector<std::string> names;
  for (int n = body.first; n <= body.last && n <= int(blanked.size()); ++n) {
    const std::size_t k = std::size_t(n - 1);
    std::smatch m;
    if (k >= lines.size() || !std::regex_search(blanked[k], m, declaration)) continue;
    const std::string type = m[4].str(), name = m[5].str();
    std::string after = blanked[k].substr(std::size_t(m.position(0) + m.length(0)));
    for (int j = n + 1; j <= body.last && j <= int(blanked.size()); ++j)
      after += blanked[std::size_t(j - 1)];
    std::smatch use;
    if (!std::regex_search(after, use, std::regex("\\b" + name + "\\b(\\s*[-+*/]=)?")) ||
        !use[1].matched)
      continue;
    const bool eigen = type.rfind("Eigen::", 0) == 0;
    const std::string start =
        one ? (eigen ? type + "::Ones()" : "1") : (eigen ? type + "::Zero()" : "0");
    const std::size_t at = std::size_t(m.position(5) + m.length(5));
    patched[k] = lines[k].substr(0, at) + " = " + start + lines[k].substr(at);
    repair.lines.push_back({file, n, trimmed(lines[k])});
    names.push_back(name);
  }
  if (repair.lines.empty()) return std::nullopt;
  for (const std::string& line : patched) repair.patched += line;
  std::string which;
  for (std::size_t k = 0; k < names.size(); ++k)
    which += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + codeSpan(names[k]);
  repair.what = one ? lineList(repair.lines) + " starting " + which + " at 1 instead of " +
                          "whatever the stack held"
                    : lineList(repair.lines) + " repaired (" + which + " starting at zero, not " +
                          "at whatever the stack held)";
  return repair;
}

}  // namespace

std::vector<Repair> repairsOf(const std::string& file, const std::string& source,
                              const std::string& stub) {
  std::vector<Repair> repairs;
  const StubLines body = stubLines(source, stub);
  if (body.first == 0) return repairs;
  const std::vector<std::string> lines = linesOf(source);
  const std::vector<std::string> blanked = linesOf(blankedCode(source));
  for (const Pattern& pattern : patternsOf(stub)) {
    Repair repair{file, stub, pattern.cause, {}, {}, {}};
    std::vector<std::string> patched = lines;
    for (int n = body.first; n <= body.last && n <= int(lines.size()); ++n) {
      const std::size_t k = std::size_t(n - 1);
      if (k >= blanked.size() || !std::regex_search(blanked[k], pattern.found)) continue;
      if (pattern.fix) {
        // Only the code is repaired: a comment at the end of the line stays as written.
        std::size_t code_end = lines[k].size();
        for (std::size_t c = 0; c + 1 < lines[k].size() && c < blanked[k].size(); ++c)
          if (lines[k].compare(c, 2, "//") == 0 && blanked[k][c] == ' ') {
            code_end = c;
            break;
          }
        const std::string code = lines[k].substr(0, code_end);
        const std::string fixed = pattern.fix(code);
        if (fixed == code) continue;
        patched[k] = fixed + lines[k].substr(code_end);
      }
      repair.lines.push_back({file, n, trimmed(lines[k])});
    }
    if (repair.lines.empty()) continue;
    if (!pattern.fix) {
      // The guard goes right after the body's opening brace, on its line (line numbers stay).
      const std::size_t k = std::size_t(body.first - 1);
      const std::size_t brace = blanked[k].find('{');
      if (brace == std::string::npos) continue;
      patched[k] = lines[k].substr(0, brace + 1) +
                   " struct ClothrefRestore_ { float v = deltaTime; ~ClothrefRestore_() { "
                   "deltaTime = v; } } clothref_restore_;" +
                   lines[k].substr(brace + 1);
    }
    for (const std::string& line : patched) repair.patched += line;
    repair.what =
        pattern.fix ? lineList(repair.lines) + " repaired (" + pattern.what + ")" : pattern.what;
    repairs.push_back(repair);
  }
  if (auto repair = localReferenceRepair(file, stub, lines, blanked, body))
    repairs.push_back(*repair);
  if (auto repair = uninitialisedSumRepair(file, stub, lines, blanked, body))
    repairs.push_back(*repair);
  return repairs;
}

std::optional<Repair> unsetStartProbe(const std::string& file, const std::string& source,
                                      const std::string& stub) {
  const StubLines body = stubLines(source, stub);
  if (body.first == 0) return std::nullopt;
  return uninitialisedSumRepair(file, stub, linesOf(source), linesOf(blankedCode(source)), body,
                                true);
}

}  // namespace clothref::grader
