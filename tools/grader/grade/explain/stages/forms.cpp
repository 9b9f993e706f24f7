// Exact forms of the stage fit (stages.h): small rationals, sums of coef * h^power * generator,
// and the same sums in the course's terms (x0 + h/2·v1), both ways.
#include <algorithm>
#include <cstdlib>
#include <numeric>

#include "grader/grade/explain/stages/stages.h"

namespace clothref::grader::stages {

Rational::Rational(std::int64_t n, std::int64_t d) : num(n), den(d) {
  if (den < 0) num = -num, den = -den;
  if (den == 0) num = 0, den = 1;  // never made by the fit; kept finite
  const std::int64_t g = std::gcd(num < 0 ? -num : num, den);
  if (g > 1) num /= g, den /= g;
}
Rational operator+(Rational a, Rational b) {
  return {a.num * b.den + b.num * a.den, a.den * b.den};
}
Rational operator-(Rational a, Rational b) {
  return {a.num * b.den - b.num * a.den, a.den * b.den};
}
Rational operator*(Rational a, Rational b) { return {a.num * b.num, a.den * b.den}; }
Rational operator/(Rational a, Rational b) { return {a.num * b.den, a.den * b.num}; }
bool operator==(Rational a, Rational b) { return a.num == b.num && a.den == b.den; }
std::string text(Rational r) {
  return r.den == 1 ? std::to_string(r.num) : std::to_string(r.num) + "/" + std::to_string(r.den);
}

bool operator==(const Term& a, const Term& b) {
  return a.gen == b.gen && a.power == b.power && a.coef == b.coef;
}

Form add(const Form& a, const Form& b) {
  Form out;
  std::size_t i = 0, j = 0;
  const auto before = [](const Term& x, const Term& y) {
    return x.gen != y.gen ? x.gen < y.gen : x.power < y.power;
  };
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && before(a[i], b[j]))) {
      out.push_back(a[i++]);
    } else if (i == a.size() || before(b[j], a[i])) {
      out.push_back(b[j++]);
    } else {
      Term t = a[i++];
      t.coef = t.coef + b[j++].coef;
      if (!t.coef.zero()) out.push_back(t);
    }
  }
  return out;
}

Form scaled(const Form& a, Rational c, int extra_power) {
  Form out;
  if (c.zero()) return out;
  for (Term t : a) {
    t.coef = t.coef * c;
    t.power += extra_power;
    out.push_back(t);
  }
  return out;
}

namespace {

Form single(int gen, int power, Rational coef) {
  return coef.zero() ? Form{} : Form{Term{gen, power, coef}};
}

// The exact form of the position or velocity of state `index` of `body` (0 = x0 / v0, k =
// evaluation k, recorded + 1 = the result); false when it has none.
bool stateForm(const StageFit& fit, int body, int index, bool position, Form& out) {
  if (index == 0) {
    out = single(position ? kGenX0 : kGenV0, 0, 1);
    return true;
  }
  if (index < 1 || index > int(fit.states.size())) return false;
  const StageState& s = fit.states[std::size_t(index - 1)];
  const Fitted* f = position ? &s.x : &s.v;
  if (body == kSpheres && s.spheres == SpheresAre::AtStart)
    return stateForm(fit, body, 0, position, out);
  if (body == kSpheres && s.spheres == SpheresAre::NoFit) return false;
  if (body == kSpheres && s.spheres == SpheresAre::Own) f = position ? &s.sphere_x : &s.sphere_v;
  if (!f->fits) return false;
  out = f->form;
  return true;
}
bool velocityForm(const StageFit& fit, int body, int index, Form& out) {
  return stateForm(fit, body, index, false, out);
}
bool positionForm(const StageFit& fit, int body, int index, Form& out) {
  return stateForm(fit, body, index, true, out);
}

}  // namespace

bool introduces(const Form& v, int& gen, Rational& d) {
  int top = -1;
  for (const Term& t : v) top = std::max(top, t.gen);
  if (top < genA(0)) return false;
  for (const Term& t : v)
    if (t.gen == top && t.power == 1) {
      gen = top;
      d = t.coef;
      return true;
    }
  return false;
}

namespace {

struct KnownVelocity {
  int index;
  Form form;
};

// `rest` written as course terms, peeling accelerations from the highest: a position's h²·a_k
// (and a velocity's h²·a_k mix-up) through the first carrier velocity that introduces a_k.
std::vector<CourseTerm> peel(Form rest, bool position, const std::vector<KnownVelocity>& carriers,
                             const std::vector<int>& state_of_gen) {
  std::vector<CourseTerm> terms;
  const int via_power = 2;  // h·v_c = h·v0 + h²·(... a)
  while (!rest.empty()) {
    const Term top = *std::max_element(rest.begin(), rest.end(), [](const Term& a, const Term& b) {
      return a.gen != b.gen ? a.gen < b.gen : a.power > b.power;
    });
    if (top.gen >= genA(0) && top.power == via_power) {
      bool done = false;
      for (const KnownVelocity& c : carriers) {
        int gen = 0;
        Rational d;
        if (introduces(c.form, gen, d) && gen == top.gen) {
          const Rational e = top.coef / d;
          terms.push_back({e, 1, 'v', c.index});
          rest = add(rest, scaled(c.form, Rational(0) - e, 1));
          done = true;
          break;
        }
      }
      if (done) continue;
    }
    CourseTerm t{top.coef, top.power, 'a', 0};
    if (top.gen == kGenX0) t.block = 'x';
    if (top.gen == kGenV0) t.block = 'v';
    if (top.gen >= genA(0)) t.index = state_of_gen[std::size_t(top.gen - genA(0))];
    if (top.gen == kGenV0 && top.power == 0 && !position) t.power = 0;
    terms.push_back(t);
    rest = add(rest, single(top.gen, top.power, Rational(0) - top.coef));
  }
  std::sort(terms.begin(), terms.end(), [](const CourseTerm& a, const CourseTerm& b) {
    const auto rank = [](char block) { return block == 'x' ? 0 : block == 'v' ? 1 : 2; };
    if (rank(a.block) != rank(b.block)) return rank(a.block) < rank(b.block);
    return a.index != b.index ? a.index < b.index : a.power < b.power;
  });
  return terms;
}

}  // namespace

bool toForm(const StageFit& fit, const CourseForm& course, Form& out) {
  Form form;
  if (!(course.base == 'x' ? positionForm(fit, kCloth, course.base_index, form)
                           : velocityForm(fit, kCloth, course.base_index, form)))
    return false;
  for (const CourseTerm& t : course.terms) {
    Form block;
    if (t.block == 'x') {
      if (!positionForm(fit, kCloth, t.index, block)) return false;
    } else if (t.block == 'v') {
      if (!velocityForm(fit, kCloth, t.index, block)) return false;
    } else {
      if (t.index < 0 || t.index >= int(fit.canonical.size())) return false;
      block = single(genA(fit.canonical[std::size_t(t.index)]), 0, 1);
    }
    form = add(form, scaled(block, t.coef, t.power));
  }
  out = form;
  return true;
}

CourseForm toCourse(const StageFit& fit, const Form& form, char base, int base_index,
                    int state_index) {
  return toCourseOf(fit, form, base, base_index, state_index, kCloth);
}

CourseForm toCourseOf(const StageFit& fit, const Form& form, char base, int base_index,
                      int state_index, int body) {
  CourseForm best;
  best.base = base;
  std::vector<int> state_of_gen(fit.canonical.size());
  std::iota(state_of_gen.begin(), state_of_gen.end(), 0);
  const bool position = base == 'x';
  // Carriers: the velocities known at this state (a position may use its own, v_new).
  std::vector<KnownVelocity> known, with_own;
  const int last = std::min<int>(state_index, int(fit.states.size()));
  for (int k = 0; k <= last; ++k) {
    Form v;
    if (!velocityForm(fit, body, k, v)) continue;
    if (k < state_index) known.push_back({k, v});
    with_own.push_back({k, v});
  }
  bool have = false;
  const auto consider = [&](int index, const std::vector<KnownVelocity>& carriers) {
    Form base_form;
    if (!(position ? positionForm(fit, body, index, base_form)
                   : velocityForm(fit, body, index, base_form)))
      return;
    CourseForm c;
    c.base = base;
    c.base_index = index;
    c.terms = peel(add(form, scaled(base_form, -1)), position, carriers, state_of_gen);
    // The previous state as base only when it says the same in fewer terms, and not in none
    // (x0 + h·v0 is clearer than "x1, unchanged").
    const bool better = c.base_index == 0 ? c.terms.size() < best.terms.size()
                                          : c.terms.size() < best.terms.size() && !c.terms.empty();
    if (!have || better) best = c, have = true;
  };
  consider(0, known);
  if (position) consider(0, with_own);
  if (base_index > 0) {
    consider(base_index, known);
    if (position) consider(base_index, with_own);
  }
  return best;
}

}  // namespace clothref::grader::stages
