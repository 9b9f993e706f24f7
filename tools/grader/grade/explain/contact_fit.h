// What a student's contact did, measured in the course's terms (issue 33, "constants recovered by
// fitting"): for one pair of bodies before and after the student's collide(), the quantities the
// course's contact is made of (docs/course.md; formula::resolveContact) read back from the
// numbers: the position correction of each body as a multiple of penetration x normal, the
// impulse each body received along the normal, the restitution that impulse implies, and what
// changed across the normal (which the course never touches). Then, over every case of a probe,
// the one quantity that differs from the course's, when one explains them all: "your position
// correction behaves as 0.5 x overlap; the course uses 0.15".
//
// Plain data and free functions; no probe, no process: unit-tested on contacts made by hand.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace clothref::grader {

// One pair as the probe set it up and as the student's code left it. Body a is the sphere (the
// normal points from b to a, as the course's); inverse masses 0 for a fixed particle.
struct ContactCase {
  std::array<double, 3> xa{}, va{}, xb{}, vb{};                          // before (m, m/s)
  std::array<double, 3> xa_after{}, va_after{}, xb_after{}, vb_after{};  // the student's
  double inverse_mass_a = 0, inverse_mass_b = 0;                         // 1/kg
  double contact_distance = 0;                                           // r_a (+ r_b) (m)
};

// The quantities read back from one pair. A quantity that cannot be read (no penetration to
// scale a correction by, a fixed body's impulse, a pair that does not approach) is empty.
struct ContactReading {
  bool in_contact = false;                           // penetration >= 0 before the call
  bool approaching = false;                          // (v_a - v_b) . n < 0 before the call
  double penetration = 0;                            // m
  std::optional<double> correction_a, correction_b;  // x_a moved by +c p n, x_b by -c p n
  std::optional<double> impulse_a, impulse_b;        // along n, as J in v_a += J/m_a, v_b -= J/m_b
  std::optional<double> restitution;  // e such that J = -(1 + e) approach / (1/m_a + 1/m_b)
  double approach = 0;                // (v_a - v_b) . n before the call (m/s)
  // The impulse read from the body whose velocity change is the larger part of its velocity (the
  // float rounding of a heavy body's tiny change can be percents), and its relative uncertainty;
  // none when both bodies are fixed or no reading is better than kReadable.
  std::optional<double> impulse;
  double impulse_uncertainty = 0;
  double inverse_mass_a = 0, inverse_mass_b = 0;
  double tangential_velocity = 0;  // largest change across the normal, relative to |v_rel|
  double tangential_position = 0;  // largest move across the normal, relative to the penetration
};

// An impulse read to worse than this (relative) says nothing about a constant.
inline constexpr double kReadable = 1e-4;

ContactReading readContact(const ContactCase& c);

// A finding over every pair of a probe: the quantity that differs (id from the catalogue when one
// names it), the value that fits and the course's, and the text a student reads. Empty when the
// readings agree with the course everywhere, or when no single quantity explains them.
struct ContactFinding {
  std::string quantity;  // "position correction", "restitution", "impulse split", ...
  std::string cause;     // catalogue id: correction-factor, restitution-ignored, ...
  double value = 0, course = 0;
  std::string text;
};

// `restitution` and `correction` are the course's constants for this contact (0 or 0.8; 0.15).
// The tolerances are relative (the student's float arithmetic: 1e-3 of the quantity is far above
// its rounding and far below any mistake the course's constants allow).
std::vector<ContactFinding> explainContacts(const std::vector<ContactReading>& readings,
                                            double restitution, double correction);

// The contact distance read back from the corrections: when every touching pair's correction
// moves each body by correction x (penetration + d) instead of correction x penetration (the
// student's contact distance is the course's + d, e.g. `radius + 0.1`), the d that fits all of
// them; none when fewer than two pairs can be read, they disagree, or d is 0.
std::optional<double> contactDistanceOffset(const std::vector<ContactReading>& readings,
                                            double correction);

}  // namespace clothref::grader
