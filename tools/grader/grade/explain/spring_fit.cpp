#include "grader/grade/explain/spring_fit.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "grader/grade/cause_ids.h"

namespace clothref::grader {
namespace {

using V3 = std::array<double, 3>;

double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The change a form predicts per unit k_s (column 0) and per unit k_d (column 1), 3 rows per
// particle.
struct Columns {
  std::vector<double> spring, damper;
};

Columns columns(const SpringCase& c, SpringForm form) {
  const std::size_t n = c.x.size();
  Columns out{std::vector<double>(3 * n, 0.0), std::vector<double>(3 * n, 0.0)};
  const auto weight = [&](int i) {
    const double m = c.mass[std::size_t(i)];
    if (form == SpringForm::MassNotInverse) return m;
    return m == 0 ? 0.0 : 1 / m;
  };
  for (const SpringCase::Spring& s : c.springs) {
    const V3& xs = c.x[std::size_t(s.start)];
    const V3& xe = c.x[std::size_t(s.end)];
    const V3 d = {xs[0] - xe[0], xs[1] - xe[1], xs[2] - xe[2]};
    const double length = std::sqrt(dot(d, d));
    if (length == 0) continue;
    const V3 unit = {d[0] / length, d[1] / length, d[2] / length};
    const V3& vs = c.v[std::size_t(s.start)];
    const V3& ve = c.v[std::size_t(s.end)];
    const V3 dv = {vs[0] - ve[0], vs[1] - ve[1], vs[2] - ve[2]};
    const double stretch = length - s.rest;
    const bool raw =
        form == SpringForm::DamperUnnormalised || form == SpringForm::DamperUnnormalisedTwice;
    const double along = raw ? dot(dv, d) : dot(dv, unit);
    const V3& damper_direction = form == SpringForm::DamperUnnormalisedTwice ? d : unit;
    for (int k = 0; k < 3; ++k) {
      const std::size_t rs = 3 * std::size_t(s.start) + std::size_t(k);
      const std::size_t re = 3 * std::size_t(s.end) + std::size_t(k);
      if (form != SpringForm::EndOnly) {
        out.spring[rs] -= unit[k] * stretch * weight(s.start);
        out.damper[rs] -= damper_direction[k] * along * weight(s.start);
      }
      if (form == SpringForm::OneEndOnly) continue;
      out.spring[re] += unit[k] * stretch * weight(s.end);
      out.damper[re] += damper_direction[k] * along * weight(s.end);
    }
  }
  return out;
}

std::string fiveDigits(double value) {
  std::ostringstream out;
  out.precision(5);
  out << value;
  return out.str();
}

bool same(double a, double b) {
  return std::abs(a - b) <= 1e-3 * std::max(std::abs(a), std::abs(b));
}

}  // namespace

SpringReading readSprings(const SpringCase& c, double relative) {
  std::vector<double> y;
  for (const V3& a : c.change) y.insert(y.end(), a.begin(), a.end());
  double yy = 0;
  for (double value : y) yy += value * value;
  SpringReading best;
  best.residual = 1e300;
  for (const SpringForm form :
       {SpringForm::Course, SpringForm::DamperUnnormalised, SpringForm::DamperUnnormalisedTwice,
        SpringForm::OneEndOnly, SpringForm::EndOnly, SpringForm::MassNotInverse}) {
    const Columns col = columns(c, form);
    // Least squares on two columns (normal equations in double: two unknowns, well scaled).
    double ss = 0, sd = 0, dd = 0, sy = 0, dy = 0;
    for (std::size_t r = 0; r < y.size(); ++r) {
      ss += col.spring[r] * col.spring[r];
      sd += col.spring[r] * col.damper[r];
      dd += col.damper[r] * col.damper[r];
      sy += col.spring[r] * y[r];
      dy += col.damper[r] * y[r];
    }
    SpringReading reading;
    reading.form = form;
    // A damper column of nothing (every particle at rest) reads k_s alone.
    if (dd <= 1e-18 * std::max(ss, 1e-300)) {
      reading.spring_coef = ss > 0 ? sy / ss : 0;
      reading.damper_coef = std::nan("");
    } else {
      const double det = ss * dd - sd * sd;
      if (std::abs(det) <= 1e-12 * ss * dd) continue;
      reading.spring_coef = (sy * dd - dy * sd) / det;
      reading.damper_coef = (dy * ss - sy * sd) / det;
    }
    double rr = 0;
    const double kd = std::isnan(reading.damper_coef) ? 0 : reading.damper_coef;
    for (std::size_t r = 0; r < y.size(); ++r) {
      const double e = y[r] - reading.spring_coef * col.spring[r] - kd * col.damper[r];
      rr += e * e;
    }
    reading.residual = yy > 0 ? std::sqrt(rr / yy) : (rr > 0 ? 1e300 : 0);
    reading.fits = reading.residual <= relative;
    if (reading.fits) return reading;
    if (reading.residual < best.residual) best = reading;
  }
  return best;
}

std::vector<SpringFinding> explainSprings(const std::vector<SpringReading>& readings,
                                          double spring_coef, double damper_coef) {
  std::vector<SpringFinding> findings;
  const auto add = [&](const std::string& id, const std::string& text) {
    for (const SpringFinding& f : findings)
      if (f.cause == id) return;
    findings.push_back({id, text});
  };
  for (const SpringReading& r : readings) {
    if (!r.fits) return {};  // a form no reading explains: no finding is confirmed
    if (r.form == SpringForm::DamperUnnormalised)
      add(cause::kDamperNotNormalised,
          "the damper's relative velocity is projected on the spring vector x_s - x_e, not on its "
          "unit direction");
    if (r.form == SpringForm::DamperUnnormalisedTwice)
      add(cause::kDamperNotNormalised,
          "the damper is k_d ((v_s - v_e) . d) d with the spring vector d = x_s - x_e unnormalised "
          "in both places, L^2 times the course's k_d ((v_s - v_e) . n) n");
    if (r.form == SpringForm::OneEndOnly)
      add(cause::kForceOneEndOnly, "only the start particle of each spring gets the force");
    if (r.form == SpringForm::EndOnly)
      add(cause::kForceOneEndOnly, "only the end particle of each spring gets the force");
    if (r.form == SpringForm::MassNotInverse)
      add(cause::kMassNotInverse, "the force is multiplied by the mass, not the inverse mass");
  }
  // The constants, over the readings that can read them, must agree to be named.
  const auto common = [&](auto get) -> std::optional<double> {
    std::optional<double> value;
    for (const SpringReading& r : readings) {
      const double v = get(r);
      if (std::isnan(v)) continue;
      if (value && !same(*value, v)) return std::nullopt;
      if (!value) value = v;
    }
    return value;
  };
  const std::optional<double> ks = common([](const SpringReading& r) { return r.spring_coef; });
  const std::optional<double> kd = common([](const SpringReading& r) { return r.damper_coef; });
  // Both terms flipped is one mistake: the whole force applied the wrong way round (the ends or
  // += and -= swapped).
  if (ks && kd && same(*ks, -spring_coef) && same(*kd, -damper_coef)) {
    add(cause::kSpringForceSign,
        "the whole force has the wrong sign, the Hooke and the damper terms both (k_s fits as " +
            fiveDigits(*ks) + " N/m, k_d as " + fiveDigits(*kd) +
            " N s/m): a stretched spring pushes its ends apart");
    return findings;
  }
  if (ks && !same(*ks, spring_coef)) {
    if (same(*ks, -spring_coef))
      add(cause::kSpringForceSign,
          "a stretched spring pushes its ends apart: the Hooke term's sign is flipped");
    else
      add(cause::kSpringCoefficient, "your spring force behaves as k_s = " + fiveDigits(*ks) +
                                         " N/m; the course's springCoef is " +
                                         fiveDigits(spring_coef));
  }
  if (kd && !same(*kd, damper_coef)) {
    if (std::abs(*kd) <= 1e-3 * damper_coef)
      add(cause::kMissingDamper, "the force has no damper term (k_d fits as 0)");
    else if (same(*kd, -damper_coef))
      add(cause::kDamperSign, "the damper adds energy: its sign is flipped");
    else
      add(cause::kDamperCoefficient, "your damper behaves as k_d = " + fiveDigits(*kd) +
                                         " N s/m; the course's damperCoef is " +
                                         fiveDigits(damper_coef));
  }
  return findings;
}

}  // namespace clothref::grader
