// fitStages (stages.h): every recorded state of a student's integrate() as an exact combination
// of the course's building blocks.
//
// A quantity is first fitted by least squares (double, Householder QR with column pivoting, columns
// scaled to unit length) on the generators it may causally depend on: for a position x0, h·v0 and
// h²·a_k, for a velocity v0 and h·a_k, a_k for every evaluation made before it (evaluations at a
// state met before share one generator). The accelerations are generic nonlinear functions of the
// state, so these columns are independent. The coefficients are then turned into small rationals
// (denominators 1..12) from the highest acceleration down, in the course's terms: a position's
// h²·a_k through the velocity that introduced a_k (h·v_k; so RK4's h²/4·a0 is h/2·v1), and a
// dimensional mix-up as a term of its own (h·a_k in a position, h·v_k in a velocity: 1/h and h
// times the natural size, told apart by that size). The rational combination then has to reproduce
// every recorded number to within kUlps float roundings of the magnitudes involved; only then does
// the quantity "fit".
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "grader/grade/explain/stages/stages.h"

namespace clothref::grader::stages {
namespace {

// A coefficient this close to a small rational is taken as that rational (a quarter of the
// smallest gap between two of them, 1/132); the residual test decides in the end.
constexpr double kSnap = 2e-3;
// How far a mix-up may move a coefficient from its natural rational: |rational| * h, h <= 0.01.
constexpr double kWindow = 0.03;

struct Snap {
  Rational r;
  double dist = std::numeric_limits<double>::infinity();
};

// The largest coefficient of the course's terms taken as exact: the course's are at most 1 (2 in
// a stage written with a doubled step); a mix-up's 1/h-sized share must not pass for one.
constexpr double kMaxCoefficient = 16;

Snap nearest(double x) {
  Snap best;
  if (!std::isfinite(x) || std::abs(x) > kMaxCoefficient + 0.5) return best;
  for (int d = 1; d <= kMaxDenominator; ++d) {
    const double n = std::round(x * d);
    const double dist = std::abs(x - n / d);
    if (dist < best.dist - 1e-15) best = {Rational(std::int64_t(n), d), dist};
  }
  return best;
}

// The small rationals within `window` of x, nearest first (0 first among equals).
std::vector<Rational> around(double x, double window) {
  std::vector<Rational> found;
  if (!std::isfinite(x) || std::abs(x) > kMaxCoefficient + 0.5) return found;
  for (int d = 1; d <= kMaxDenominator; ++d)
    for (double n = std::ceil((x - window) * d); n <= std::floor((x + window) * d); ++n) {
      const Rational r(std::int64_t(n), d);
      if (std::find(found.begin(), found.end(), r) == found.end()) found.push_back(r);
    }
  std::stable_sort(found.begin(), found.end(), [x](Rational a, Rational b) {
    return std::abs(x - a.value()) < std::abs(x - b.value());
  });
  return found;
}

struct Carrier {
  Form form;  // h·(this velocity) is added as scaled(form, e, 1)
};

// A split of one coefficient into its two levels (fit.cpp header): the natural level alone
// first, then one level alone, then the simplest rationals, then the closest.
struct Choice {
  Rational big;
  Snap small;
  bool natural = false;     // the level a correct stub uses is the only one (position: B = 0)
  bool other_zero = false;  // the other level is zero (a pure mix-up)
  bool ok() const { return small.dist <= kSnap; }
  std::int64_t complexity() const { return big.den + small.r.den; }
  bool better(const Choice& than) const {
    if (ok() != than.ok()) return ok();
    if (natural != than.natural) return natural;
    if (other_zero != than.other_zero) return other_zero;
    if (complexity() != than.complexity()) return complexity() < than.complexity();
    return small.dist < than.small.dist;
  }
};

// The column power of a generator in a position (x0, h·v0, h²·a) or velocity (v0, h·a) fit.
int columnPower(bool position, int gen) {
  if (gen == kGenX0) return 0;
  if (gen == kGenV0) return position ? 1 : 0;
  return position ? 2 : 1;
}

// One attempt at turning least-squares coefficients `beta` (by generator, at column power) into
// an exact form, with the given carrier velocities.
Form rationalForm(std::map<int, double> rem, bool position, double h,
                  const std::vector<Carrier>& carriers) {
  Form form;
  const auto take = [&](const Form& part) {
    form = add(form, part);
    for (const Term& t : part) {
      auto it = rem.find(t.gen);
      if (it != rem.end())
        it->second -= t.coef.value() * std::pow(h, t.power - columnPower(position, t.gen));
    }
  };
  std::vector<int> gens;
  for (const auto& [gen, value] : rem)
    if (gen >= genA(0)) gens.push_back(gen);
  for (auto g = gens.rbegin(); g != gens.rend(); ++g) {
    const double b = rem[*g];
    const Carrier* carrier = nullptr;
    Rational d;
    for (const Carrier& c : carriers) {
      int gen = 0;
      if (introduces(c.form, gen, d) && gen == *g) {
        carrier = &c;
        break;
      }
    }
    // b = S + B/h (position) or B + S·h (velocity): B on h·a_g, S on h²·a_g (through a carrier).
    std::vector<Rational> bs = position ? around(b * h, kWindow) : around(b, kWindow);
    if (position) bs.insert(bs.begin(), Rational(0));
    Choice best;
    for (Rational big : bs) {
      const double s = position ? b - big.value() / h : (b - big.value()) / h;
      const Snap snap = nearest(carrier ? s / d.value() : s);
      const Choice c{big, snap, position ? big.zero() : snap.r.zero(),
                     position ? snap.r.zero() : big.zero()};
      if (c.better(best)) best = c;
    }
    const Rational best_b = best.big;
    const Snap best_s = best.small;
    take(best_b.zero() ? Form{} : Form{Term{*g, 1, best_b}});
    if (carrier)
      take(scaled(carrier->form, best_s.r, 1));
    else if (!best_s.r.zero())
      take(Form{Term{*g, 2, best_s.r}});
  }
  if (rem.count(kGenV0)) {
    const double b = rem[kGenV0];
    if (position) {
      const Snap e = nearest(b);
      if (!e.r.zero()) take(Form{Term{kGenV0, 1, e.r}});
    } else {
      Choice best;
      for (Rational big : around(b, kWindow)) {
        const Snap snap = nearest((b - big.value()) / h);
        const Choice c{big, snap, snap.r.zero(), big.zero()};
        if (c.better(best)) best = c;
      }
      if (!best.big.zero()) take(Form{Term{kGenV0, 0, best.big}});
      if (!best.small.r.zero()) take(Form{Term{kGenV0, 1, best.small.r}});
    }
  }
  if (rem.count(kGenX0)) {
    const Snap xi = nearest(rem[kGenX0]);
    if (!xi.r.zero()) take(Form{Term{kGenX0, 0, xi.r}});
  }
  return form;
}

// Fits `recorded` (a position or velocity of `body`) on the generators x0 / v0 and a_g (g in
// `gens`); `carriers` in the order they are tried, each list of carriers an attempt.
Fitted fitQuantity(const StageFit& fit, int body, bool position, const std::vector<int>& gens,
                   const std::vector<std::vector<Carrier>>& attempts,
                   const std::vector<double>& recorded) {
  Fitted out;
  const double h = fit.record.h;
  std::vector<int> columns = {position ? kGenX0 : kGenV0};
  if (position) columns.push_back(kGenV0);
  for (int g : gens) columns.push_back(genA(g));
  const Eigen::Index n = Eigen::Index(recorded.size());
  Eigen::MatrixXd m(n, Eigen::Index(columns.size()));
  std::vector<double> norms;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::vector<double>& col = column(fit, body, columns[c]);
    const double scale = std::pow(h, columnPower(position, columns[c]));
    double norm = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      m(i, Eigen::Index(c)) = i < Eigen::Index(col.size()) ? scale * col[std::size_t(i)] : 0.0;
      norm += m(i, Eigen::Index(c)) * m(i, Eigen::Index(c));
    }
    norm = std::sqrt(norm);
    norms.push_back(norm);
    if (norm > 0) m.col(Eigen::Index(c)) /= norm;
  }
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(recorded.data(), n);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  qr.setThreshold(1e-10);
  const Eigen::VectorXd solution =
      n > 0 ? Eigen::VectorXd(qr.solve(q)) : Eigen::VectorXd::Zero(Eigen::Index(columns.size()));
  std::map<int, double> beta;
  Form least;  // the unrounded fit, as a residual only
  double worst = 0;
  for (std::size_t c = 0; c < columns.size(); ++c)
    beta[columns[c]] = norms[c] > 0 && std::isfinite(solution(Eigen::Index(c)))
                           ? solution(Eigen::Index(c)) / norms[c]
                           : 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    double value = 0, magnitude = std::abs(q(i));
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double term = m(i, Eigen::Index(c)) * norms[c] * beta[columns[c]];
      value += term;
      magnitude += std::abs(term);
    }
    worst = std::max(worst, std::abs(q(i) - value) / (kUlps * kUnit * magnitude + 1e-300));
  }
  out.least_squares = worst;
  out.residual = std::numeric_limits<double>::infinity();
  for (const auto& carriers : attempts) {
    const Form form = rationalForm(beta, position, h, carriers);
    const double r = formResidual(fit, body, form, recorded);
    if (r < out.residual) out.form = form, out.residual = r;
    if (r <= 1) break;
  }
  out.fits = out.residual <= 1;
  return out;
}

bool sameState(const BodyState& a, const BodyState& b) { return a.x == b.x && a.v == b.v; }

const BodyState& stateOf(const StageRecord& r, int index, int body) {
  return recordedState(r, index, body);
}

// Carrier attempts for a quantity of state q: the velocities before it (and, for a position, its
// own), then without its own, then none (h²·a terms written out).
std::vector<std::vector<Carrier>> attemptsFor(const std::vector<Form>& velocities, bool position,
                                              const Form* own) {
  std::vector<Carrier> before;
  for (const Form& v : velocities) before.push_back({v});
  std::vector<std::vector<Carrier>> attempts;
  if (position && own) {
    attempts.push_back(before);
    attempts.back().push_back({*own});
  }
  attempts.push_back(before);
  attempts.push_back({});
  return attempts;
}

}  // namespace

const BodyState& recordedState(const StageRecord& r, int index, int body) {
  if (index == 0) return r.start[std::size_t(body)];
  if (index <= int(r.evaluations.size()))
    return r.evaluations[std::size_t(index - 1)][std::size_t(body)];
  return r.result[std::size_t(body)];
}

const std::vector<double>& column(const StageFit& fit, int body, int gen) {
  static const std::vector<double> none;
  const StageRecord& r = fit.record;
  const std::size_t b = std::size_t(body);
  if (gen == kGenX0) return r.start[b].x;
  if (gen == kGenV0) return r.start[b].v;
  const int k = gen - genA(0);
  if (k == 0) return r.start[b].a;
  if (k >= 1 && k <= int(r.evaluations.size())) return r.evaluations[std::size_t(k - 1)][b].a;
  return none;
}

double formResidual(const StageFit& fit, int body, const Form& form,
                    const std::vector<double>& recorded) {
  std::vector<double> value(recorded.size(), 0.0), magnitude(recorded.size(), 0.0);
  for (std::size_t i = 0; i < recorded.size(); ++i) magnitude[i] = std::abs(recorded[i]);
  for (const Term& t : form) {
    const std::vector<double>& col = column(fit, body, t.gen);
    if (col.size() != recorded.size()) return std::numeric_limits<double>::infinity();
    const double c = t.coef.value() * std::pow(fit.record.h, t.power);
    for (std::size_t i = 0; i < recorded.size(); ++i) {
      value[i] += c * col[i];
      magnitude[i] += std::abs(c * col[i]);
    }
  }
  double worst = 0;
  for (std::size_t i = 0; i < recorded.size(); ++i) {
    const double r = std::abs(recorded[i] - value[i]) / (kUlps * kUnit * magnitude[i] + 1e-300);
    if (!std::isfinite(r)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, r);
  }
  return worst;
}

StageFit fitStages(const StageRecord& record) {
  StageFit fit;
  fit.record = record;
  fit.recorded = int(std::min<std::size_t>(record.evaluations.size(), kMaxRecordedCalls));
  fit.record.evaluations.resize(std::size_t(fit.recorded));
  const StageRecord& r = fit.record;
  // a_k's generator: the first evaluation (or the start) with the cloth in the same state.
  fit.canonical.push_back(0);
  for (int k = 1; k <= fit.recorded; ++k) {
    int same = k;
    for (int j = 0; j < k && same == k; ++j)
      if (sameState(stateOf(r, k, kCloth), stateOf(r, j, kCloth)))
        same = fit.canonical[std::size_t(j)];
    fit.canonical.push_back(same);
  }
  std::vector<Form> velocities = {Form{Term{kGenV0, 0, Rational(1)}}};  // fitted v_k, k < q
  for (int q = 1; q <= fit.recorded + 1; ++q) {
    StageState s;
    const BodyState& cloth = stateOf(r, q, kCloth);
    for (int j = 0; j < q && j <= fit.recorded && s.same_as < 0; ++j)
      if (sameState(cloth, stateOf(r, j, kCloth))) s.same_as = j;
    std::vector<int> gens;
    for (int k = 0; k < q && k <= fit.recorded; ++k)
      if (std::find(gens.begin(), gens.end(), fit.canonical[std::size_t(k)]) == gens.end())
        gens.push_back(fit.canonical[std::size_t(k)]);
    std::sort(gens.begin(), gens.end());
    s.v = fitQuantity(fit, kCloth, false, gens, attemptsFor(velocities, false, nullptr), cloth.v);
    s.x = fitQuantity(fit, kCloth, true, gens,
                      attemptsFor(velocities, true, s.v.fits ? &s.v.form : nullptr), cloth.x);
    // The spheres: at the cloth's stage, at their start, at a stage of their own, or none.
    const BodyState& spheres = stateOf(r, q, kSpheres);
    if (!spheres.x.empty()) {
      const bool same = s.x.fits && s.v.fits &&
                        formResidual(fit, kSpheres, s.x.form, spheres.x) <= 1 &&
                        formResidual(fit, kSpheres, s.v.form, spheres.v) <= 1;
      if (!same && sameState(spheres, r.start[kSpheres]) && s.same_as != 0) {
        s.spheres = SpheresAre::AtStart;
      } else if (!same) {
        // Their accelerations hardly change between stages (gravity), so a0 stands for them all.
        const Form v0{Term{kGenV0, 0, Rational(1)}};
        s.sphere_v = fitQuantity(fit, kSpheres, false, {0}, {{{v0}}}, spheres.v);
        std::vector<std::vector<Carrier>> own = {{{v0}, {s.sphere_v.form}}, {{v0}}};
        s.sphere_x = fitQuantity(fit, kSpheres, true, {0}, own, spheres.x);
        s.spheres = s.sphere_x.fits && s.sphere_v.fits ? SpheresAre::Own : SpheresAre::NoFit;
      }
    }
    if (s.v.fits)
      velocities.push_back(s.v.form);
    else
      velocities.push_back(Form{});  // keeps the index; introduces nothing
    fit.states.push_back(s);
  }
  // The course's terms, once every velocity is known (a position may use its own).
  for (int q = 1; q <= int(fit.states.size()); ++q) {
    StageState& s = fit.states[std::size_t(q - 1)];
    if (s.x.fits) s.x.course = toCourse(fit, s.x.form, 'x', q - 1, q);
    if (s.v.fits) s.v.course = toCourse(fit, s.v.form, 'v', q - 1, q);
    if (s.spheres == SpheresAre::Own) {
      s.sphere_x.course = toCourseOf(fit, s.sphere_x.form, 'x', 0, q, kSpheres);
      s.sphere_v.course = toCourseOf(fit, s.sphere_v.form, 'v', 0, q, kSpheres);
    }
  }
  return fit;
}

}  // namespace clothref::grader::stages
