// Trace reading: parses a clothref trace (JSON Lines, docs/trace-format.md) back into numbers.
//
// Inputs: a trace file path ("-" for standard input; gzip-compressed input, such as a .jsonl.gz
// file, is recognised by its first byte and decompressed). Line 1 is the header (parsed with
// nlohmann::json, matched by key); each further line is one recorded step, parsed by a small
// hand-written parser (std::from_chars) because a DOM per 40 kB line is slow. Keys are matched by
// name in any order; unknown keys, missing keys, wrong array shapes and truncated lines are errors.
// A header line longer than inputLimits().header_bytes, a step line longer than line_bytes, and
// headers declaring more particles or steps than the limits allow (io/limits.h) are refused before
// anything is allocated for them. Outputs:
// TraceHeader; per step the step number, t (seconds, double), the 64-bit state hash and, on
// request, every body's positions (m) and velocities (m/s) as flat x,y,z arrays (3 per particle) in
// the header's body order. Float traces are parsed as float (exact bits) and widened. Non-finite
// values, written as "NaN", "Infinity", "-Infinity" (strings, as clothref writes them, or bare
// tokens, as Python's json.dumps writes them), come back as NaN and +-infinity; t too. Every error
// is an InputError "FILE:LINE: problem".
#pragma once

#include <cstdint>
#include <fstream>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "clothref/base/precision.h"

namespace clothref {

class GzipInputBuffer;

// One body as declared in the header ("bodies": [{"name": "cloth", "particles": 625}, ...]).
struct TraceBody {
  std::string name;
  std::int64_t particles = 0;
};

struct TraceHeader {
  nlohmann::ordered_json json;  // the whole header object, as written
  int version = 0;
  Precision precision = Precision::Float;
  std::string integrator;
  double dt = 0;            // seconds
  std::int64_t steps = 0;   // steps simulated
  std::int64_t stride = 1;  // every stride-th step recorded, plus the last
  std::vector<TraceBody> bodies;
};

// The cheap part of a step line: the first three keys, read without touching the arrays.
struct StepPrefix {
  std::int64_t step = 0;
  double t = 0;  // seconds
  std::uint64_t hash = 0;
};

// One body's state at one step: 3 * particles values each, particle-major (x0, y0, z0, x1, ...).
struct BodyState {
  std::vector<double> position;  // metres
  std::vector<double> velocity;  // metres / second
};

struct TraceStep {
  StepPrefix prefix;
  std::vector<BodyState> bodies;  // in TraceHeader::bodies order
};

// Reads a trace line by line. Usage:
//   TraceReader reader(path);                 // reads and validates the header
//   while (reader.next()) {                   // reads the next step line and its prefix
//     if (need_values) reader.parseStep(step);
//   }
class TraceReader {
 public:
  // Opens `path` ("-": standard input) and parses line 1; throws InputError for a missing file
  // or a bad header.
  explicit TraceReader(const std::string& path);
  ~TraceReader();
  // Reads from `in` (a pipe, a string, a file already open), which must outlive the reader;
  // `source` names it in messages.
  TraceReader(std::istream& in, const std::string& source);

  // The file name or source messages use.
  const std::string& path() const { return path_; }
  const TraceHeader& header() const { return header_; }

  // Reads the next step line and parses its prefix (step, t, hash). Returns false at the end of
  // the file. Throws InputError if the prefix is malformed or the step does not increase.
  bool next();

  // The current line (without its newline), its 1-based line number and prefix.
  std::string_view line() const { return line_; }
  std::int64_t lineNumber() const { return line_number_; }
  const StepPrefix& prefix() const { return prefix_; }

  // Parses the whole current line into `step` (reusing its storage); throws InputError, also when
  // the header's hash is clothref's (kTraceHashDescription) and the step's "hash" is not that of
  // its values (a corrupt or edited record; steps holding NaN excepted, see docs/trace-format.md).
  void parseStep(TraceStep& step) const;

  // Throws InputError("FILE:LINE: problem") for the current line.
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  void readHeader();
  // Reads one line of at most `limit` bytes into line_ (longer: an error naming `flag`); false at
  // the end of the input.
  bool readLine(bool& ended_with_newline, std::size_t limit, const char* what, const char* flag);

  std::string path_;
  std::unique_ptr<std::ifstream> owned_;   // set when the reader opened the file itself
  std::unique_ptr<GzipInputBuffer> gzip_;  // set for gzip-compressed input
  std::unique_ptr<std::istream> gzip_stream_;
  std::istream* in_ = nullptr;
  std::string line_;
  std::int64_t line_number_ = 0;
  TraceHeader header_;
  StepPrefix prefix_;
  bool has_step_ = false;
  bool own_hash_ = false;  // the header's hash is kTraceHashDescription: parseStep checks it
};

// The check of a header's "scene" beyond its being an object: unknown keys at any depth, types,
// ranges. trace/ never sees a scene (docs/layout.md), so the code that knows scenes supplies it:
// the CLI installs the scene reader at start (tools/clothref/main.cpp); without one (nullptr, the
// default) only the shape is checked. It throws InputError naming the JSON pointer inside the
// scene ("/cloth/spring_cof: unknown key"), reported as "FILE:1: header: /scene/cloth/...".
using HeaderSceneCheck = void (*)(const nlohmann::ordered_json& scene);
void setHeaderSceneCheck(HeaderSceneCheck check);

// Parses a header object (already read as JSON); throws InputError("SOURCE:1: problem").
TraceHeader parseTraceHeader(const nlohmann::ordered_json& json, const std::string& source);

// The state hash (trace/hash.h) of a parsed step's values in the header's precision: what the
// step's "hash" is when the header's "hash" is kTraceHashDescription (trace/format.h).
std::uint64_t stateHashOf(const TraceHeader& header, const TraceStep& step);

// Reads a whole trace into memory (convenient for small traces and tests).
struct Trace {
  TraceHeader header;
  std::vector<TraceStep> steps;
};
Trace readTrace(const std::string& path);

}  // namespace clothref
