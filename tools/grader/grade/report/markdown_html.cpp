// The grader's Markdown as HTML (markdown_html.h).
#include "grader/grade/report/markdown_html.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "pages/html.h"

namespace clothref::grader {
namespace {

std::size_t backtickRun(std::string_view text, std::size_t at) {
  std::size_t n = 0;
  while (at + n < text.size() && text[at + n] == '`') ++n;
  return n;
}

// Inline Markdown of one line, escaped: code spans (a run of N backticks up to the next run of
// exactly N, as text.h's codeSpan writes them) and **bold**; everything else is text.
std::string inlineMarkdown(std::string_view line) {
  std::string out;
  bool bold = false;
  for (std::size_t i = 0; i < line.size();) {
    if (line[i] == '`') {
      const std::size_t n = backtickRun(line, i);
      std::size_t close = i + n;
      while (close < line.size()) {
        close = line.find('`', close);
        if (close == std::string_view::npos) break;
        const std::size_t m = backtickRun(line, close);
        if (m == n) break;
        close += m;
      }
      if (close == std::string_view::npos || close >= line.size()) {  // no closing run: text
        out += line.substr(i, n);
        i += n;
        continue;
      }
      std::string_view code = line.substr(i + n, close - i - n);
      if (code.size() >= 2 && code.front() == ' ' && code.back() == ' ' &&
          code.find_first_not_of(' ') != std::string_view::npos)
        code = code.substr(1, code.size() - 2);
      out += "<code>" + pages::escapeHtml(code) + "</code>";
      i = close + n;
    } else if (line.compare(i, 2, "**") == 0) {
      out += bold ? "</strong>" : "<strong>";
      bold = !bold;
      i += 2;
    } else {
      const std::size_t next = std::min(line.find('`', i), line.find("**", i));
      const std::size_t end = next == std::string_view::npos ? line.size() : next;
      out += pages::escapeHtml(line.substr(i, end - i));
      i = end;
    }
  }
  if (bold) out += "</strong>";
  return out;
}

}  // namespace

std::string markdownToHtml(std::string_view markdown) {
  std::string out;
  std::istringstream lines{std::string(markdown)};
  std::string line;
  std::size_t fence = 0;  // the open fence's length, 0 outside a code block
  bool paragraph = false, table = false;
  // the open lists' indents, outermost first; each one's last <li> stays open for a nested list
  std::vector<std::size_t> lists;
  const auto closeLists = [&](std::size_t keep) {
    for (; lists.size() > keep; lists.pop_back()) out += "</li>\n</ul>\n";
  };
  const auto close = [&] {
    closeLists(0);
    if (paragraph) out += "</p>\n";
    if (table) out += "</table>\n";
    paragraph = table = false;
  };
  // "| a | b |" rows: the first is the header, a "|---|" row under it is dropped; "\|" is a '|'
  // inside a cell.
  const auto cells = [](const std::string& row) {
    std::vector<std::string> found;
    std::string cell;
    bool open = false;
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (row[k] == '\\' && k + 1 < row.size() && row[k + 1] == '|') {
        cell += '|';
        ++k;
      } else if (row[k] == '|') {
        if (open) {
          const std::size_t first = cell.find_first_not_of(' ');
          found.push_back(first == std::string::npos
                              ? std::string()
                              : cell.substr(first, cell.find_last_not_of(' ') - first + 1));
        }
        open = true;
        cell.clear();
      } else {
        cell += row[k];
      }
    }
    return found;
  };
  while (std::getline(lines, line)) {
    const std::size_t run = backtickRun(line, 0);
    // a fence opens with three backticks or more and closes with a line of as many or more
    if (!fence && run >= 3) {
      close();
      out += "<pre><code>";
      fence = run;
      continue;
    }
    if (fence && run >= fence && line.find_first_not_of("` ", run) == std::string::npos) {
      out += "</code></pre>\n";
      fence = 0;
      continue;
    }
    if (fence) {
      out += pages::escapeHtml(line) + "\n";
      continue;
    }
    if (line.find_first_not_of(" \t") == std::string::npos) {
      close();
      continue;
    }
    const std::size_t indent = line.find_first_not_of(' ');
    if (line[indent] == '|' && line.find('|', indent + 1) != std::string::npos) {
      if (line.find_first_not_of("|-: ") == std::string::npos) continue;  // the separator row
      const bool header = !table;
      if (!table) close();
      if (!table) out += "<table>\n";
      table = true;
      out += "<tr>";
      for (const std::string& cell : cells(line))
        out += (header ? "<th>" : "<td>") + inlineMarkdown(cell) + (header ? "</th>" : "</td>");
      out += "</tr>\n";
      continue;
    }
    if (table) out += "</table>\n";
    table = false;
    if (line.compare(indent, 2, "- ") == 0) {
      if (paragraph) out += "</p>\n";
      paragraph = false;
      // deeper than the open item: a list inside it; else back out to the item's own level
      while (lists.size() > 1 && indent < lists.back()) closeLists(lists.size() - 1);
      if (lists.empty() || indent > lists.back()) {
        out += lists.empty() ? "<ul>\n<li>" : "\n<ul>\n<li>";
        lists.push_back(indent);
      } else {
        out += "</li>\n<li>";
      }
      out += inlineMarkdown(std::string_view(line).substr(indent + 2));
      continue;
    }
    closeLists(0);
    if (line.rfind("#", 0) == 0) {
      if (paragraph) out += "</p>\n";
      paragraph = false;
      out += "<p><strong>" + inlineMarkdown(line.substr(line.find_first_not_of('#'))) +
             "</strong></p>\n";
      continue;
    }
    out += (paragraph ? "\n" : "<p>") + inlineMarkdown(line);
    paragraph = true;
  }
  if (fence) out += "</code></pre>\n";
  close();
  return out;
}

std::string testHtml(const TestText& text) {
  std::string out = markdownToHtml(text.output);
  for (const auto& [blocks, css] :
       {std::pair{&text.likely, "gr-likely"}, std::pair{&text.guesses, "gr-guesses"}})
    if (!blocks->empty()) {
      out += std::string("<div class=\"") + css + "\">";
      for (const std::string& block : *blocks) out += markdownToHtml(block);
      out += "</div>\n";
    }
  return out;
}

}  // namespace clothref::grader
