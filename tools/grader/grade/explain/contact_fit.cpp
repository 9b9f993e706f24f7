#include "grader/grade/explain/contact_fit.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "grader/grade/cause_ids.h"

namespace clothref::grader {
namespace {

using V3 = std::array<double, 3>;

V3 minus(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }
V3 scaled(const V3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

// |part of `d` across `n`|.
double across(const V3& d, const V3& n) { return norm(minus(d, scaled(n, dot(d, n)))); }

// Quantities agree to 1e-3 of the larger (far above float rounding, far below any mistake).
constexpr double kAgree = 1e-3;
bool same(double a, double b) {
  return std::abs(a - b) <= kAgree * std::max({1.0, std::abs(a), std::abs(b)});
}

// A value read back, to the agreement it was read with: -2e-9 is 0 (a restitution of 0 read
// through float roundings), not a number a student should chase.
std::string readBack(double value) {
  std::ostringstream out;
  out.precision(4);
  out << (std::abs(value) <= kAgree ? 0.0 : value);
  return out.str();
}

// The one value every reading has for `quantity`, or none (no reading, or two that differ).
template <typename Get>
std::optional<double> common(const std::vector<ContactReading>& readings, Get&& get) {
  std::optional<double> value;
  for (const ContactReading& r : readings) {
    const std::optional<double> v = get(r);
    if (!v) continue;
    if (value && !same(*value, *v)) return std::nullopt;
    if (!value) value = v;
  }
  return value;
}

}  // namespace

ContactReading readContact(const ContactCase& c) {
  ContactReading r;
  V3 n = minus(c.xa, c.xb);
  const double length = norm(n);
  r.penetration = c.contact_distance - length;
  r.in_contact = r.penetration >= 0;
  if (!r.in_contact || length == 0) return r;
  n = scaled(n, 1 / length);
  const double approach = dot(minus(c.va, c.vb), n);
  r.approaching = approach < 0;
  r.approach = approach;
  r.inverse_mass_a = c.inverse_mass_a;
  r.inverse_mass_b = c.inverse_mass_b;
  const V3 dxa = minus(c.xa_after, c.xa), dxb = minus(c.xb_after, c.xb);
  const V3 dva = minus(c.va_after, c.va), dvb = minus(c.vb_after, c.vb);
  // A correction scales with the penetration: readable only when there is one.
  if (r.penetration > 1e-6 * c.contact_distance) {
    r.correction_a = dot(dxa, n) / r.penetration;
    r.correction_b = -dot(dxb, n) / r.penetration;
    r.tangential_position = std::max(across(dxa, n), across(dxb, n)) / r.penetration;
  }
  if (c.inverse_mass_a > 0) r.impulse_a = dot(dva, n) / c.inverse_mass_a;
  if (c.inverse_mass_b > 0) r.impulse_b = -dot(dvb, n) / c.inverse_mass_b;
  const double relative = norm(minus(c.va, c.vb));
  if (relative > 0) r.tangential_velocity = std::max(across(dva, n), across(dvb, n)) / relative;
  // The better-read impulse gives the restitution: a float velocity is rounded to about 2^-24 of
  // itself, so a change of dv in a velocity of size |v| is known to |v| 2^-24 / |dv|.
  const auto uncertainty = [](const V3& before, const V3& change) {
    const double moved = norm(change);
    return moved > 0 ? 6e-8 * (norm(before) + moved) / moved : 1e300;
  };
  const double ua = r.impulse_a ? uncertainty(c.va, dva) : 1e300;
  const double ub = r.impulse_b ? uncertainty(c.vb, dvb) : 1e300;
  r.impulse = ua <= ub ? r.impulse_a : r.impulse_b;
  r.impulse_uncertainty = std::min(ua, ub);
  if (r.impulse_uncertainty > kReadable) r.impulse.reset();
  if (r.approaching && r.impulse)
    r.restitution = -*r.impulse * (c.inverse_mass_a + c.inverse_mass_b) / approach - 1;
  return r;
}

std::vector<ContactFinding> explainContacts(const std::vector<ContactReading>& readings,
                                            double restitution, double correction) {
  std::vector<ContactFinding> findings;
  std::vector<ContactReading> touching;
  for (const ContactReading& r : readings)
    if (r.in_contact) touching.push_back(r);
  if (touching.empty()) return findings;

  // Velocities: the impulse on separating pairs, across the normal, its split and its size.
  bool impulse_when_separating = false, impulses_match = true;
  for (const ContactReading& r : touching) {
    const bool pushed = (r.impulse_a && std::abs(*r.impulse_a) > 1e-9) ||
                        (r.impulse_b && std::abs(*r.impulse_b) > 1e-9);
    if (!r.approaching && pushed) impulse_when_separating = true;
    if (r.approaching && r.impulse && r.impulse_a && r.impulse_b &&
        !same(*r.impulse_a, *r.impulse_b))
      impulses_match = false;
  }
  const double tangential =
      std::max_element(touching.begin(), touching.end(), [](const auto& a, const auto& b) {
        return a.tangential_velocity < b.tangential_velocity;
      })->tangential_velocity;
  const std::optional<double> e =
      common(touching, [](const ContactReading& r) { return r.restitution; });
  const bool velocities_right = !impulse_when_separating && impulses_match &&
                                tangential <= kAgree && e && same(*e, restitution);
  if (impulse_when_separating)
    findings.push_back({"approach test", cause::kNoApproachCheck, 0, 0,
                        "an impulse is applied to pairs that already move apart"});
  if (tangential > kAgree)
    findings.push_back({"normal velocity", cause::kRestitutionFullVelocity, tangential, 0,
                        "the impulse changes the velocity across the contact normal too (by " +
                            readBack(100 * tangential) +
                            " % of the relative speed); the course changes only its normal part"});
  if (!impulses_match) {
    const std::optional<double> ratio = common(touching, [](const ContactReading& r) {
      return r.approaching && r.impulse_a && r.impulse_b && *r.impulse_b != 0
                 ? std::optional<double>(*r.impulse_a / *r.impulse_b)
                 : std::nullopt;
    });
    findings.push_back({"impulse split", cause::kWrongMassSplit, ratio.value_or(0), 1,
                        "the two bodies do not receive equal and opposite impulses" +
                            (ratio ? " (the sphere's is " + readBack(*ratio) + " x the other's)"
                                   : std::string())});
  } else if (e && !same(*e, restitution)) {
    // (beside an impulse on separating pairs too: two mistakes, each its own finding)
    findings.push_back({"restitution", cause::kRestitutionIgnored, *e, restitution,
                        "your bounce behaves as a coefficient of restitution of " + readBack(*e) +
                            "; the course's is " + readBack(restitution)});
  } else if (!impulse_when_separating && !e) {
    // No one restitution fits every pair: the impulse's denominator is not the course's
    // 1/m_a + 1/m_b. Which one does fit: none (J = -(1 + e) approach), or m_a + m_b.
    const auto denominator = [&](const ContactReading& r) -> std::optional<double> {
      if (!r.approaching || !r.impulse || *r.impulse == 0) return std::nullopt;
      return -(1 + restitution) * r.approach / *r.impulse;
    };
    const auto matches = [&](auto form) {
      bool any = false;
      for (const ContactReading& r : touching) {
        const std::optional<double> d = denominator(r);
        if (!d) continue;
        any = true;
        if (!same(*d, form(r))) return false;
      }
      return any;
    };
    const auto mass = [](double inverse) { return inverse > 0 ? 1 / inverse : 0.0; };
    if (matches([](const ContactReading&) { return 1.0; }))
      findings.push_back({"impulse split", cause::kWrongMassSplit, 1, 0,
                          "the impulse -(1 + e) v_rel.n is not divided by 1/m_a + 1/m_b, so the "
                          "bounce depends on the masses"});
    else if (matches([&](const ContactReading& r) {
               return mass(r.inverse_mass_a) + mass(r.inverse_mass_b);
             }))
      findings.push_back({"impulse split", cause::kWrongMassSplit, 0, 0,
                          "the impulse is divided by m_a + m_b, not by 1/m_a + 1/m_b"});
  }

  // Positions: the correction of each body as a multiple of penetration x normal.
  const std::optional<double> ca =
      common(touching, [](const ContactReading& r) { return r.correction_a; });
  const std::optional<double> cb =
      common(touching, [](const ContactReading& r) { return r.correction_b; });
  const bool across_positions =
      std::any_of(touching.begin(), touching.end(),
                  [](const ContactReading& r) { return r.tangential_position > kAgree; });
  if (!ca || !cb || across_positions || (same(*ca, correction) && same(*cb, correction)))
    return findings;
  const std::string only_positions =
      velocities_right ? "velocities equal the course's; only positions differ: " : "";
  if (same(*ca, -correction) && same(*cb, -correction)) {
    findings.push_back({"normal direction", cause::kCollisionNormalSign, -1, 1,
                        only_positions + "the correction pulls the bodies together (your normal "
                                         "points the other way)"});
  } else if (same(*ca, 0) && same(*cb, 0)) {
    findings.push_back({"position correction", cause::kNoPositionCorrection, 0, correction,
                        only_positions + "penetrating bodies are not pushed apart"});
  } else if (same(*ca, 0) != same(*cb, 0) && (same(*ca, correction) || same(*cb, correction))) {
    findings.push_back(
        {"position correction", cause::kCorrectionOneBody, same(*ca, 0) ? *cb : *ca, correction,
         only_positions + "only " + std::string(same(*ca, 0) ? "the other body" : "the sphere") +
             " is pushed out (" + readBack(correction) + " x overlap); the course moves both"});
  } else if (same(*ca, 0) != same(*cb, 0)) {
    // One body pushed out by another factor, the other not at all: two mistakes, each its own
    // finding (the factor is the moved body's, so a model of both can be replayed).
    const double moved = same(*ca, 0) ? *cb : *ca;
    const std::string who = same(*ca, 0) ? "the other body" : "the sphere";
    findings.push_back({"position correction", cause::kCorrectionOneBody, moved, correction,
                        only_positions + "only " + who + " is pushed out; the course moves both"});
    findings.push_back({"position correction", cause::kCorrectionFactor, moved, correction,
                        only_positions + "your position correction behaves as " + readBack(moved) +
                            " x overlap for " + who + " and 0 for " +
                            (same(*ca, 0) ? "the sphere" : "the other body") +
                            "; the course uses " + readBack(correction) + " for both"});
  } else if (same(*ca, *cb)) {
    findings.push_back({"position correction", cause::kCorrectionFactor, *ca, correction,
                        only_positions + "your position correction behaves as " + readBack(*ca) +
                            " x overlap; the course uses " + readBack(correction)});
  } else {
    findings.push_back({"position correction", cause::kCorrectionFactor, *ca, correction,
                        only_positions + "your position correction behaves as " + readBack(*ca) +
                            " x overlap for the sphere and " + readBack(*cb) +
                            " x for the other body; the course uses " + readBack(correction) +
                            " for both"});
  }
  return findings;
}

std::optional<double> contactDistanceOffset(const std::vector<ContactReading>& readings,
                                            double correction) {
  std::optional<double> offset;
  int read = 0;
  for (const ContactReading& r : readings) {
    if (!r.correction_a || !r.correction_b || r.tangential_position > kAgree) continue;
    // Each body moved by correction x (penetration + d) along the normal.
    const double da = *r.correction_a * r.penetration / correction - r.penetration;
    const double db = *r.correction_b * r.penetration / correction - r.penetration;
    if (!std::isfinite(da) || !same(da, db)) return std::nullopt;
    if (offset && !same(*offset, da)) return std::nullopt;
    if (!offset) offset = da;
    ++read;
  }
  if (read < 2 || !offset || std::abs(*offset) <= kAgree) return std::nullopt;
  return offset;
}

}  // namespace clothref::grader
