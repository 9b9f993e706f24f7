// Likely causes of a wrong first step (diagnosis.h).
#include "grader/grade/probes/integrate/diagnosis.h"

#include <Eigen/QR>
#include <algorithm>
#include <array>

#include "clothref/core/integrator.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/stages/methods.h"
#include "grader/grade/explain/stages/stages.h"
#include "grader/grade/mistakes/integrate_mistakes.h"
#include "grader/grade/submission/source_text.h"
#include "grader/grade/submission/submission.h"

namespace clothref::grader::integrators {
namespace {

// RK4's final update fitted as x0 + sum w_k kx_k (and v0 + sum u_k kv_k) over the cloth, with the
// stages of the course method. Empty when the update is no such sum.
struct WeightFit {
  bool fits = false;
  Eigen::Vector4d w = Eigen::Vector4d::Zero();
};
std::pair<WeightFit, WeightFit> fitRk4Weights(const System& random, const System& actual) {
  // The course's stages: the library's RK4 keeps every body's start and k in its scratch.
  System s = random;
  simulate(s);
  std::array<Particles<float>*, 2> storage{&s.cloth.particles, &s.spheres.particles};
  IntegratorScratch<float> scratch;
  auto sim = [&] { simulate(s); };
  integrateRk4(Bodies<float>(storage.data(), storage.size()), s.dt, FunctionRef<void()>(sim),
               scratch);
  const BodyScratch<float>& cloth = scratch[0];
  const auto fit = [](const Mat4X<float>(&k)[4], const Mat4X<float>& start,
                      const Mat4X<float>& end) {
    WeightFit result;
    const Eigen::Index n = start.size();
    Eigen::MatrixXd a(n, 4);
    for (int j = 0; j < 4; ++j)
      a.col(j) = Eigen::Map<const Eigen::VectorXf>(k[j].data(), n).cast<double>();
    const Eigen::VectorXd b = (Eigen::Map<const Eigen::VectorXf>(end.data(), n) -
                               Eigen::Map<const Eigen::VectorXf>(start.data(), n))
                                  .cast<double>();
    result.w = a.colPivHouseholderQr().solve(b);
    const double scale = 1e-12 + a.cwiseAbs().rowwise().sum().norm();
    result.fits = result.w.allFinite() && (a * result.w - b).norm() <= 1e-4 * scale;
    return result;
  };
  return {fit(cloth.kx, cloth.x0, actual.cloth.particles.position),
          fit(cloth.kv, cloth.v0, actual.cloth.particles.velocity)};
}

bool near(const Eigen::Vector4d& w, const Eigen::Vector4d& target) {
  return (w - target).cwiseAbs().maxCoeff() < 1e-3;
}

// The known mistakes of `method` that change the first step, as (cause id, its step): the
// student's numbers equal to one of these name that cause.
std::vector<std::pair<std::string, Step>> oneStepSignatures(Method method) {
  std::vector<std::pair<std::string, Step>> signatures;
  for (const Reading& r : readingsOf(method))
    if (r.first_pass) signatures.push_back({r.id, courseStep(StepModel{method, {r.row}, {}})});
  return signatures;
}

// RK4 whose first step matches no signature: right stages, other weights? Fits both updates on
// the course's stages, says what they fit in `output`, and returns the cause ("" = none).
std::string rk4WeightCause(const IntegratorRun& run, const std::string& source,
                           std::string& output) {
  const auto [x, v] = fitRk4Weights(run.random, run.actual);
  const Eigen::Vector4d course = Eigen::Map<const Eigen::Vector4d>(stages::kRk4Weights.data());
  const Eigen::Vector4d zero = Eigen::Vector4d::Zero();
  const bool missing_term = (x.fits && near(x.w, zero)) || (v.fits && near(v.w, zero)) ||
                            (x.fits && x.w[0] == 0 && near(x.w, {0, 1.0 / 3, 1.0 / 3, 0}));
  for (const auto& [what, fit] : {std::pair{"position", x}, std::pair{"velocity", v}})
    if (fit.fits && !near(fit.w, course))
      output += "\nYour " + std::string(what) + " update fits x0 + " + util::num(fit.w[0]) +
                " k1 + " + util::num(fit.w[1]) + " k2 + " + util::num(fit.w[2]) + " k3 + " +
                util::num(fit.w[3]) + " k4 (the course: 1/6, 1/3, 1/3, 1/6).\n";
  // A weight of zero where the course has 1/6 is integer division only when the source has it.
  if (missing_term && sourceHints(source).integer_sixth) return cause::kIntegerDivisionRk4;
  // The course's weights on k read from other stages (k1 read after stage 4 overwrote the
  // state): the literal weights are right, a k is not.
  const auto restaged = [&](const WeightFit& f) {
    return !f.fits || near(f.w, course) ||
           stages::courseWeightsOnOtherStages({f.w[0], f.w[1], f.w[2], f.w[3]}, 1e-3);
  };
  if (((x.fits && !near(x.w, course)) || (v.fits && !near(v.w, course))) && restaged(x) &&
      restaged(v))
    return cause::kRk4MixedIncrements;
  if ((x.fits && !near(x.w, course)) || (v.fits && !near(v.w, course)))
    return cause::kRk4WrongWeights;
  return "";
}

}  // namespace

std::string stubSource(const ProbeContext& context, const std::string& stub) {
  auto file = context.sources.find("integrator.cpp");
  return file == context.sources.end() ? "" : stubCode(file->second, stub);
}

std::vector<std::string> diagnoseOneStep(const ProbeContext& context, const IntegratorRun& run,
                                         std::string& output, std::vector<std::string>& guesses) {
  const Method method = run.method;
  const std::vector<std::pair<std::string, Step>> signatures = oneStepSignatures(method);
  std::vector<std::string> ids;
  const auto add = [&](const std::string& id) {
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  };
  const auto drop = [&](const std::string& id) {
    ids.erase(std::remove(ids.begin(), ids.end(), id), ids.end());
  };
  for (const auto& [id, step] : signatures)
    if (distance(run.actual, stepped(run.random, step)) <= 10 * run.rel) add(id);
  // Nothing added by the final update is integer division only when the source divides 1 by 6.
  const std::string source = stubSource(context, run.stub);
  const SourceHints hints = sourceHints(source);
  // A backup's numbers from a stub whose backup is a real copy: the corrector steps from the
  // prediction (the source tells the two apart; the numbers cannot).
  const auto alias = std::find(ids.begin(), ids.end(), cause::kBackupAlias);
  if (alias != ids.end() && (method == Method::Implicit || method == Method::Midpoint) &&
      copiesButNoView(hints))
    *alias = cause::kCorrectorFromPrediction;
  if (std::find(ids.begin(), ids.end(), cause::kIntegerDivisionRk4) != ids.end() &&
      !source.empty() && !hints.integer_sixth) {
    drop(cause::kIntegerDivisionRk4);
    add(cause::kRk4WrongWeights);
  }

  if (ids.empty() && method == Method::Rk4) {
    const std::string id = rk4WeightCause(run, source, output);
    if (!id.empty()) add(id);
  }
  const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
  if (!after.empty() && after[0] != run.random.dt) add(cause::kDeltatimeMutated);

  // simulateOneStep calls during integrate: the method's evaluations but the one before it.
  const auto& calls_out = run.answer.i(key::perCase(key::kCalls, 0));
  const std::int64_t calls = calls_out.empty() ? -1 : calls_out[0];
  const std::int64_t expected_calls = methodInfo(method).evaluations - 1;
  if (calls >= 0 && calls != expected_calls)
    output += "\nsimulateOneStep() was called " + std::to_string(calls) +
              " times during integrate(); the course method calls it " +
              std::to_string(expected_calls) + " times.\n";
  if (calls >= 0 && calls < expected_calls) {
    drop(cause::kNoReevaluation);
    add(cause::kNoReevaluation);
  } else if (method == Method::Midpoint && calls == expected_calls &&
             distance(run.actual, stepped(run.random, readingStep(cause::kIntegerDivisionHalf,
                                                                  method))) <= 10 * run.rel) {
    // simulateOneStep() ran at the start state: the half step added nothing, or was never written
    // back. Integer division only when the source divides 1 by 2.
    if (hints.integer_half) {
      drop(cause::kNoReevaluation);
      add(cause::kIntegerDivisionHalf);
    }
  }
  // RK4 that called simulateOneStep() three times and then kept only k1 gives explicit Euler's
  // numbers: the stages were discarded, not skipped.
  if (method == Method::Rk4 && calls == expected_calls &&
      std::find(ids.begin(), ids.end(), cause::kRk4StagesDiscarded) != ids.end())
    drop(cause::kNoReevaluation);
  if (calls >= 0 && calls < expected_calls) drop(cause::kRk4StagesDiscarded);
  // A per-body loop calls simulateOneStep() once per body and stage.
  if (calls > expected_calls && expected_calls > 0 && calls % expected_calls == 0 &&
      std::find(ids.begin(), ids.end(), cause::kPerBodyLoop) == ids.end() && ids.empty())
    guesses.push_back(cause::kPerBodyLoop);
  return ids;
}

}  // namespace clothref::grader::integrators
