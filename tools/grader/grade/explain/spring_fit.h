// What a student's spring force did, measured in the course's terms (issue 33, "constants
// recovered by fitting"): the change the student's computeSpringForce made to the accelerations,
// over a whole cloth, fitted as the course's force with its constants free, F = n (k_d ((v_s -
// v_e) . n) + k_s (L - rest)) applied as -F / m_s and +F / m_e. Read back: the k_s and k_d that
// fit (a sign flipped, a damper missing, a constant scaled), and whether another form fits
// where the course's does not (the damper on the unnormalised spring vector, one end only, the
// mass where its inverse belongs). "Your spring force behaves as k_s = 12500 N/m; the course's
// springCoef is 25000."
//
// Plain data and free functions, no probe: unit-tested on forces made here.
#pragma once
#include <array>
#include <string>
#include <vector>

namespace clothref::grader {

struct SpringCase {
  std::vector<std::array<double, 3>> x, v;  // positions (m), velocities (m/s), per particle
  std::vector<double> mass;                 // kg (0: fixed)
  struct Spring {
    int start, end;
    double rest;  // m
  };
  std::vector<Spring> springs;
  std::vector<std::array<double, 3>> change;  // the student's a_after - a_before (m/s^2)
};

// The forms a reading tries, in order: the course's, then each single change of form.
enum class SpringForm {
  Course,
  DamperUnnormalised,       // k_d ((v_s - v_e) . d) n, d = x_s - x_e: L times the course's
  DamperUnnormalisedTwice,  // k_d ((v_s - v_e) . d) d: L^2 times the course's
  OneEndOnly,               // only the start particle gets -F / m_s
  EndOnly,                  // only the end particle gets +F / m_e
  MassNotInverse
};

struct SpringReading {
  bool fits = false;  // some form explains the change to rounding
  SpringForm form = SpringForm::Course;
  double spring_coef = 0;  // k_s that fits (N/m)
  double damper_coef = 0;  // k_d that fits (N s/m)
  double residual = 0;     // |change - fit| / |change| of the best form
};

// `relative` is the fit the change must reach (force_rel, the probe's tolerance).
SpringReading readSprings(const SpringCase& c, double relative);

struct SpringFinding {
  std::string cause;  // catalogue id
  std::string text;   // for the student
};

// The causes the readings of a probe's cases confirm, each once, against the course's constants.
std::vector<SpringFinding> explainSprings(const std::vector<SpringReading>& readings,
                                          double spring_coef, double damper_coef);

}  // namespace clothref::grader
