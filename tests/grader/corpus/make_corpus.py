#!/usr/bin/env python3
"""Writes the realistic grader corpus (tests/grader/corpus/): submissions written the way real
students write them, each combining several mistakes across the three files, with comments, odd
formatting and, in some, Big5-encoded comments (the bytes are committed as written here).

Run from anywhere: python3 tests/grader/corpus/make_corpus.py

Each submission is the course-form reference (tools/grader/reference/<edition>/) with the bodies of
some stubs replaced by a student's version written below. Its labels.json holds the hand verdict
per stub ("full" or "loses") and, for a stub that loses points, the cause ids
(tools/grader/diagnoses.json) found by reading the code, plus "also": ids that are consistent with
the code too (a consequence, e.g. a crash's verdict). Labels come from reasoning about the code,
never from the grader's output.
"""
import json
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "submissions"))
import make_corpus as base  # noqa: E402  (the reference files and the stub locator)

FILES = base.FILES


def body(edition, stub):
    text = base.reference(edition)[base.STUB_HEAD[stub][0]]
    start, end = base.function_span(text, stub)
    return text[start:end]


# ---- Student bodies. `@BIG5:` comments become Big5 bytes in a Big5 submission, UTF-8 otherwise.

SPRINGS_SHEAR_STRUCTURAL = """\
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // @BIG5:垂直的結構彈簧
  for(int i=0;i<particlesPerEdge-1;i++)
    for(int j=0;j<particlesPerEdge;j++)
      _springs.emplace_back(i*particlesPerEdge+j, (i+1)*particlesPerEdge+j, structrualLength, Spring::Type::STRUCTURAL);
  // @BIG5:斜的彈簧 兩個方向
  for(int i=0;i<particlesPerEdge-1;i++){
    for(int j=0;j<particlesPerEdge-1;j++){
      _springs.emplace_back(i*particlesPerEdge+j, (i+1)*particlesPerEdge+j+1, structrualLength, Spring::Type::SHEAR);
      _springs.emplace_back(i*particlesPerEdge+j+1, (i+1)*particlesPerEdge+j, structrualLength, Spring::Type::SHEAR);
    }
  }
  // @BIG5:彎曲彈簧 隔一個粒子
  float bendLength = (_particles.position(0) - _particles.position(2)).norm();
  for(int i=0;i<particlesPerEdge;i++)
    for(int j=0;j<particlesPerEdge-2;j++)
      _springs.emplace_back(i*particlesPerEdge+j, i*particlesPerEdge+j+2, bendLength, Spring::Type::BEND);
  for(int i=0;i<particlesPerEdge-2;i++)
    for(int j=0;j<particlesPerEdge;j++)
      _springs.emplace_back(i*particlesPerEdge+j, (i+2)*particlesPerEdge+j, bendLength, Spring::Type::BEND);
"""

# Diagonals labelled BEND and distance-2 springs labelled SHEAR (the labels swapped).
SPRINGS_TYPES_SWAPPED = """\
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  float diag = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();
  float twoApart = (_particles.position(0) - _particles.position(2)).norm();
  for (int i = 0; i < particlesPerEdge; i++) {
    for (int j = 0; j < particlesPerEdge; j++) {
      int idx = i * particlesPerEdge + j;
      if (j + 1 < particlesPerEdge) _springs.emplace_back(idx, idx + 1, structrualLength, Spring::Type::STRUCTURAL);
      if (i + 1 < particlesPerEdge) _springs.emplace_back(idx, idx + particlesPerEdge, structrualLength, Spring::Type::STRUCTURAL);
      // diagonal ones bend the cloth?
      if (i + 1 < particlesPerEdge && j + 1 < particlesPerEdge)
        _springs.emplace_back(idx, idx + particlesPerEdge + 1, diag, Spring::Type::BEND);
      if (i + 1 < particlesPerEdge && j > 0)
        _springs.emplace_back(idx, idx + particlesPerEdge - 1, diag, Spring::Type::BEND);
      if (j + 2 < particlesPerEdge) _springs.emplace_back(idx, idx + 2, twoApart, Spring::Type::SHEAR);
      if (i + 2 < particlesPerEdge) _springs.emplace_back(idx, idx + 2 * particlesPerEdge, twoApart, Spring::Type::SHEAR);
    }
  }
"""

# Everything sized for the course's 25 x 25 cloth.
SPRINGS_HARD_CODED_25 = """\
  const int N = 25;  // cloth is 25 x 25
  float L = (_particles.position(0) - _particles.position(1)).norm();
  float Ld = (_particles.position(0) - _particles.position(N + 1)).norm();
  float L2 = (_particles.position(0) - _particles.position(2)).norm();
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) {
      int k = r * N + c;
      if (c < N - 1) _springs.emplace_back(k, k + 1, L, Spring::Type::STRUCTURAL);
      if (r < N - 1) _springs.emplace_back(k, k + N, L, Spring::Type::STRUCTURAL);
      if (r < N - 1 && c < N - 1) _springs.emplace_back(k, k + N + 1, Ld, Spring::Type::SHEAR);
      if (r < N - 1 && c > 0) _springs.emplace_back(k, k + N - 1, Ld, Spring::Type::SHEAR);
      if (c < N - 2) _springs.emplace_back(k, k + 2, L2, Spring::Type::BEND);
      if (r < N - 2) _springs.emplace_back(k, k + 2 * N, L2, Spring::Type::BEND);
    }
"""

# The down-left shear diagonal forgotten.
SPRINGS_ONE_DIAGONAL = """\
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  float shear = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();
  float bend  = (_particles.position(0) - _particles.position(2)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      if (j < particlesPerEdge - 1)
        _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
      if (i < particlesPerEdge - 1)
        _springs.emplace_back(index, index + particlesPerEdge, structrualLength, Spring::Type::STRUCTURAL);
      if (i < particlesPerEdge - 1 && j < particlesPerEdge - 1)
        _springs.emplace_back(index, index + particlesPerEdge + 1, shear, Spring::Type::SHEAR);  // shear
      if (j < particlesPerEdge - 2)
        _springs.emplace_back(index, index + 2, bend, Spring::Type::BEND);
      if (i < particlesPerEdge - 2)
        _springs.emplace_back(index, index + 2 * particlesPerEdge, bend, Spring::Type::BEND);
    }
  }
"""

SPRINGS_SQRT2 = """\
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  for (int i = 0; i < particlesPerEdge - 1; ++i)
  {
    for (int j = 0; j < particlesPerEdge; ++j)
    {
      _springs.emplace_back(i * particlesPerEdge + j, (i + 1) * particlesPerEdge + j, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // diagonal = sqrt(2) * side
  float shearLength = 1.41f * structrualLength;
  for (int i = 0; i < particlesPerEdge - 1; ++i)
  {
    for (int j = 0; j < particlesPerEdge - 1; ++j)
    {
      _springs.emplace_back(i * particlesPerEdge + j, (i + 1) * particlesPerEdge + j + 1, shearLength, Spring::Type::SHEAR);
      _springs.emplace_back(i * particlesPerEdge + j + 1, (i + 1) * particlesPerEdge + j, shearLength, Spring::Type::SHEAR);
    }
  }
  float bendLength = 2.0f * structrualLength;
  for (int i = 0; i < particlesPerEdge; ++i)
  {
    for (int j = 0; j < particlesPerEdge - 2; ++j)
    {
      _springs.emplace_back(i * particlesPerEdge + j, i * particlesPerEdge + j + 2, bendLength, Spring::Type::BEND);
      _springs.emplace_back(j * particlesPerEdge + i, (j + 2) * particlesPerEdge + i, bendLength, Spring::Type::BEND);
    }
  }
"""

# Bend springs get the structural rest length.
SPRINGS_BEND_STRUCTURAL = """\
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  float shearLength = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      const int me = i * particlesPerEdge + j;
      if (j + 1 < particlesPerEdge) _springs.emplace_back(me, me + 1, structrualLength, Spring::Type::STRUCTURAL);
      if (i + 1 < particlesPerEdge) _springs.emplace_back(me, me + particlesPerEdge, structrualLength, Spring::Type::STRUCTURAL);
      if (i + 1 < particlesPerEdge && j + 1 < particlesPerEdge) _springs.emplace_back(me, me + particlesPerEdge + 1, shearLength, Spring::Type::SHEAR);
      if (i + 1 < particlesPerEdge && j >= 1) _springs.emplace_back(me, me + particlesPerEdge - 1, shearLength, Spring::Type::SHEAR);
      // bend: skip one
      if (j + 2 < particlesPerEdge) _springs.emplace_back(me, me + 2, structrualLength, Spring::Type::BEND);
      if (i + 2 < particlesPerEdge) _springs.emplace_back(me, me + 2 * particlesPerEdge, structrualLength, Spring::Type::BEND);
    }
  }
"""

# A correct force with `auto` variables that hold plain values (normalized(), norm()): safe.
FORCE_SAFE_AUTO = """\
  for (const auto& spring : _springs) {
    int s = spring.startParticleIndex();
    int e = spring.endParticleIndex();
    auto len = (_particles.position(s) - _particles.position(e)).norm();
    auto dir = (_particles.position(s) - _particles.position(e)).normalized();
    Eigen::Vector4f dv = _particles.velocity(s) - _particles.velocity(e);
    // F = -(ks (|x| - r) + kd v.d) d
    Eigen::Vector4f force = dir * (damperCoef * dv.dot(dir) + springCoef * (len - spring.length()));
    _particles.acceleration(s) -= force * _particles.inverseMass(s);
    _particles.acceleration(e) += force * _particles.inverseMass(e);
  }
"""

FORCE_DAMPER_UNNORMALISED = """\
  for (const auto& spring : _springs) {
    int a = spring.startParticleIndex(), b = spring.endParticleIndex();
    Eigen::Vector4f x = _particles.position(a) - _particles.position(b);
    Eigen::Vector4f v = _particles.velocity(a) - _particles.velocity(b);
    float len = x.norm();
    Eigen::Vector4f dir = x / len;
    // Hooke + damper
    Eigen::Vector4f F = -(springCoef * (len - spring.length()) + damperCoef * v.dot(x)) * dir;
    _particles.acceleration(a) += F * _particles.inverseMass(a);
    _particles.acceleration(b) -= F * _particles.inverseMass(b);
  }
"""

FORCE_ASSIGN = """\
  for (const auto& spring : _springs) {
    int start = spring.startParticleIndex();
    int end = spring.endParticleIndex();
    Eigen::Vector4f d = _particles.position(start) - _particles.position(end);
    float length = d.norm();
    d.normalize();
    Eigen::Vector4f relV = _particles.velocity(start) - _particles.velocity(end);
    Eigen::Vector4f F = d * (damperCoef * relV.dot(d) + springCoef * (length - spring.length()));
    // a = F / m
    _particles.acceleration(start) = -F * _particles.inverseMass(start);
    _particles.acceleration(end) = F * _particles.inverseMass(end);
  }
"""

FORCE_ONE_END = """\
  for (const auto& spring : _springs) {
    int i = spring.startParticleIndex(), j = spring.endParticleIndex();
    Eigen::Vector4f n = _particles.position(i) - _particles.position(j);
    float l = n.norm();
    n.normalize();
    float fs = springCoef * (l - spring.length());
    float fd = damperCoef * (_particles.velocity(i) - _particles.velocity(j)).dot(n);
    _particles.acceleration(i) -= (fs + fd) * n * _particles.inverseMass(i);
  }
"""

# Hooke term written (rest - length) while the rest is the course's form.
FORCE_HOOKE_SIGN = """\
  for (const auto& spring : _springs) {
    // @BIG5:彈簧的力
    int start = spring.startParticleIndex();
    int end = spring.endParticleIndex();
    Eigen::Vector4f direction = _particles.position(start) - _particles.position(end);
    float length = direction.norm();
    direction.normalize();
    Eigen::Vector4f relativeVelocity = _particles.velocity(start) - _particles.velocity(end);
    Eigen::Vector4f force = direction * (damperCoef * relativeVelocity.dot(direction) + springCoef * (spring.length() - length));
    _particles.acceleration(start) -= force * _particles.inverseMass(start);
    _particles.acceleration(end) += force * _particles.inverseMass(end);
  }
"""

FORCE_DAMPER_SIGN = """\
  for (const auto& spring : _springs) {
    int s = spring.startParticleIndex();
    int e = spring.endParticleIndex();
    Eigen::Vector4f dx = _particles.position(s) - _particles.position(e);
    float len = dx.norm();
    Eigen::Vector4f dir = dx / len;
    Eigen::Vector4f dv = _particles.velocity(e) - _particles.velocity(s);   // relative velocity
    Eigen::Vector4f force = dir * (springCoef * (len - spring.length()) + damperCoef * dv.dot(dir));
    _particles.acceleration(s) -= force * _particles.inverseMass(s);
    _particles.acceleration(e) += force * _particles.inverseMass(e);
  }
"""

# a = F / m written with the mass itself: the corners (mass 0) divide by zero.
FORCE_DIVIDE_BY_MASS = """\
  for (const auto& spring : _springs) {
    int s = spring.startParticleIndex();
    int e = spring.endParticleIndex();
    Eigen::Vector4f d = _particles.position(s) - _particles.position(e);
    float len = d.norm();
    d.normalize();
    Eigen::Vector4f F = d * (damperCoef * (_particles.velocity(s) - _particles.velocity(e)).dot(d) + springCoef * (len - spring.length()));
    _particles.acceleration(s) -= F / _particles.mass(s);
    _particles.acceleration(e) += F / _particles.mass(e);
  }
"""

# `auto` holding an Eigen expression over two temporaries (the Refs position(i) returns).
FORCE_DANGLING_AUTO = """\
  for (const auto& spring : _springs) {
    int s = spring.startParticleIndex();
    int e = spring.endParticleIndex();
    auto diff = _particles.position(s) - _particles.position(e);
    auto relVel = _particles.velocity(s) - _particles.velocity(e);
    float len = diff.norm();
    Eigen::Vector4f dir = diff / len;
    Eigen::Vector4f force = dir * (damperCoef * relVel.dot(dir) + springCoef * (len - spring.length()));
    _particles.acceleration(s) -= force * _particles.inverseMass(s);
    _particles.acceleration(e) += force * _particles.inverseMass(e);
  }
"""

# ---- Sphere-cloth contacts (coefRestitution declared first, as in the course file).


def cloth_contact(e, inner):
    return (f"  constexpr float coefRestitution = {e};\n"
            "  Particles& clothParticles = cloth->particles();\n" + inner)


CONTACT_FULL_VELOCITY = """\
  for (int i = 0; i < sphereCount; i++) {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; j++) {
      Eigen::Vector4f n = _particles.position(i) - clothParticles.position(j);
      float d = n.norm();
      if (d > _radius[i]) continue;  // no hit
      n.normalize();
      Eigen::Vector4f vrel = _particles.velocity(i) - clothParticles.velocity(j);
      if (vrel.dot(n) < 0) {
        // @BIG5:反彈
        Eigen::Vector4f J = -(1 + coefRestitution) * vrel / (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += J * _particles.inverseMass(i);
        clothParticles.velocity(j) -= J * clothParticles.inverseMass(j);
      }
      Eigen::Vector4f c = ((_radius[i] - d) * n) * 0.15f;
      _particles.position(i) += c;
      clothParticles.position(j) -= c;
    }
  }
"""

CONTACT_FIRST_SPHERE = """\
  int i = 0;  // TODO: more spheres
  for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
    Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);
    float penetration = _radius[i] - normal.norm();
    if (penetration < 0) continue;
    normal.normalize();
    float approach = (_particles.velocity(i) - clothParticles.velocity(j)).dot(normal);
    if (approach < 0) {
      Eigen::Vector4f impulse = (-(1 + coefRestitution) * (normal * approach)) /
                                (clothParticles.inverseMass(j) + _particles.inverseMass(i));
      _particles.velocity(i) += impulse * _particles.inverseMass(i);
      clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
    }
    Eigen::Vector4f correction = (penetration * normal) * 0.15f;
    _particles.position(i) += correction;
    clothParticles.position(j) -= correction;
  }
"""

# The textbook formula with masses: a fixed corner (mass 0) acts massless.
CONTACT_MASS_FORMULA = """\
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
      Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);
      float penetration = _radius[i] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      if ((_particles.velocity(i) - clothParticles.velocity(j)).dot(normal) < 0) {
        float ma = _particles.mass(i), mb = clothParticles.mass(j);
        Eigen::Vector4f ua = normal * _particles.velocity(i).dot(normal);
        Eigen::Vector4f ub = normal * clothParticles.velocity(j).dot(normal);
        // v_a' = (ma ua + mb ub + mb e (ub - ua)) / (ma + mb)
        Eigen::Vector4f va = (ma * ua + mb * ub + mb * coefRestitution * (ub - ua)) / (ma + mb);
        Eigen::Vector4f vb = (ma * ua + mb * ub + ma * coefRestitution * (ua - ub)) / (ma + mb);
        _particles.velocity(i) += va - ua;
        clothParticles.velocity(j) += vb - ub;
      }
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      clothParticles.position(j) -= correction;
    }
  }
"""

CONTACT_CORRECTION_CLOTH_ONLY = """\
  for (int i = 0; i < sphereCount; ++i)
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
      Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);
      float penetration = _radius[i] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      float approach = (_particles.velocity(i) - clothParticles.velocity(j)).dot(normal);
      if (approach < 0) {
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * (normal * approach)) / (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
      }
      // the sphere is heavy, only move the cloth
      clothParticles.position(j) -= (penetration * normal) * 0.15f;
    }
"""

CONTACT_NO_APPROACH = """\
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
      Eigen::Vector4f n = _particles.position(i) - clothParticles.position(j);
      float pen = _radius[i] - n.norm();
      if (pen >= 0) {
        n.normalize();
        // @BIG5:沿著法向量的速度
        Eigen::Vector4f vn = n * (_particles.velocity(i) - clothParticles.velocity(j)).dot(n);
        Eigen::Vector4f J = (-(1 + coefRestitution) * vn) / (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += J * _particles.inverseMass(i);
        clothParticles.velocity(j) -= J * clothParticles.inverseMass(j);
        _particles.position(i) += (pen * n) * 0.15f;
        clothParticles.position(j) -= (pen * n) * 0.15f;
      }
    }
  }
"""

CONTACT_TOUCHING_SKIPPED = """\
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
      Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);
      float dist = normal.norm();
      if (dist >= _radius[i]) continue;  // outside
      float penetration = _radius[i] - dist;
      normal /= dist;
      float approach = (_particles.velocity(i) - clothParticles.velocity(j)).dot(normal);
      if (approach < 0) {
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * (normal * approach)) /
                                  (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
      }
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      clothParticles.position(j) -= correction;
    }
  }
"""

# The normal taken from the cloth particle to the sphere, with the course's signs kept.
CONTACT_NORMAL_REVERSED = """\
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j) {
      Eigen::Vector4f normal = clothParticles.position(j) - _particles.position(i);
      float penetration = _radius[i] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      float approach = (_particles.velocity(i) - clothParticles.velocity(j)).dot(normal);
      if (approach < 0) {
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * (normal * approach)) /
                                  (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
      }
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      clothParticles.position(j) -= correction;
    }
  }
"""

CONTACT_CORRECT_STYLED = """\
  for (int i = 0; i < sphereCount; ++i)
  {
    for (int j = 0; j < particlesPerEdge * particlesPerEdge; ++j)
    {
      Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);
      float penetration = _radius[i] - normal.norm();
      if (penetration < 0)
        continue;
      normal.normalize();
      Eigen::Vector4f relativeVelocity = _particles.velocity(i) - clothParticles.velocity(j);
      float approach = relativeVelocity.dot(normal);
      if (approach < 0)
      {
        Eigen::Vector4f normalVelocity = normal * approach;
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * normalVelocity) / (clothParticles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
      }
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      clothParticles.position(j) -= correction;
    }
  }
"""

# ---- Sphere-sphere contacts (2022).


def sphere_contact(e, inner):
    return f"  constexpr float coefRestitution = {e};\n" + inner


SPHERES_NO_APPROACH = """\
  for (int i = 0; i < sphereCount; i++) {
    for (int j = i + 1; j < sphereCount; j++) {
      Eigen::Vector4f n = _particles.position(i) - _particles.position(j);
      float dist = n.norm();
      float pen = _radius[i] + _radius[j] - dist;
      if (pen < 0) continue;
      n /= dist;
      Eigen::Vector4f vr = _particles.velocity(i) - _particles.velocity(j);
      // @BIG5:碰撞的衝量
      Eigen::Vector4f J = -(1 + coefRestitution) * vr.dot(n) * n / (_particles.inverseMass(i) + _particles.inverseMass(j));
      _particles.velocity(i) += J * _particles.inverseMass(i);
      _particles.velocity(j) -= J * _particles.inverseMass(j);
      _particles.position(i) += 0.15f * pen * n;
      _particles.position(j) -= 0.15f * pen * n;
    }
  }
"""

SPHERES_COURSE = """\
  for (int i = 0; i < sphereCount; ++i) {
    for (int j = {J}; j < sphereCount; ++j) {{J_GUARD}
      Eigen::Vector4f normal = _particles.position(i) - _particles.position(j);
      float penetration = _radius[i] + _radius[j] - normal.norm();
      if (penetration < 0) continue;
      normal.normalize();
      float approach = (_particles.velocity(i) - _particles.velocity(j)).dot(normal);
      if (approach < 0) {
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * (normal * approach)) /
                                  (_particles.inverseMass(j) + _particles.inverseMass(i));
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        _particles.velocity(j) -= impulse * _particles.inverseMass(j);
      }
      Eigen::Vector4f correction = (penetration * normal) * 0.15f;
      _particles.position(i) += correction;
      {CORRECT_J}
    }
  }
"""


def spheres(j_start="i + 1", guard="", correct_j="_particles.position(j) -= correction;"):
    return (SPHERES_COURSE.replace("{J}", j_start).replace("{J_GUARD}", guard)
            .replace("{CORRECT_J}", correct_j))


# ---- Integrators.

EXPLICIT_STYLED = """\
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
"""

EXPLICIT_SYMPLECTIC = """\
  // v first, then x with the new v (semi-implicit, more stable)
  for (auto p : particles) {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
"""

EXPLICIT_WITH_ACCELERATION = """\
  for (auto& p : particles) {
    p->position() = p->position() + p->velocity() * deltaTime + 0.5f * p->acceleration() * deltaTime * deltaTime;
    p->velocity() = p->velocity() + p->acceleration() * deltaTime;
  }
"""

EXPLICIT_FIRST_BODY = """\
  Particles* cloth = particles[0];
  cloth->position() += cloth->velocity() * deltaTime;
  cloth->velocity() += cloth->acceleration() * deltaTime;
"""

IMPLICIT_POINTER_BACKUP = """\
  auto backup = particles;   // @BIG5:先備份
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (int i = 0; i < (int)particles.size(); i++) {
    particles[i]->position() = backup[i]->position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i]->velocity() + particles[i]->acceleration() * deltaTime;
  }
"""

IMPLICIT_REF_BACKUP = """\
  auto x0c = particles[0]->position();  // cloth backup
  auto v0c = particles[0]->velocity();
  auto x0s = particles[1]->position();  // spheres backup
  auto v0s = particles[1]->velocity();
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  particles[0]->position() = x0c + particles[0]->velocity() * deltaTime;
  particles[0]->velocity() = v0c + particles[0]->acceleration() * deltaTime;
  particles[1]->position() = x0s + particles[1]->velocity() * deltaTime;
  particles[1]->velocity() = v0s + particles[1]->acceleration() * deltaTime;
"""

# Predictor written as symplectic Euler (v first, x with the new v); corrector as the course.
IMPLICIT_SYMPLECTIC_PREDICTOR = """\
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  // @BIG5:先預測下一步
  for (auto p : particles) {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
"""

IMPLICIT_NO_SIMULATE = """\
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  // X(n+1) = X(n) + dt * f(X(n+1))
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
"""

# One body at a time, each with its own simulateOneStep(): the bodies are out of sync.
IMPLICIT_PER_BODY = """\
  for (auto p : particles) {
    Particles old = *p;
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
    simulateOneStep();
    p->position() = old.position() + p->velocity() * deltaTime;
    p->velocity() = old.velocity() + p->acceleration() * deltaTime;
  }
"""

MIDPOINT_SIMULATE_FIRST = """\
  std::vector<Particles> start;
  for (auto p : particles) start.push_back(*p);
  simulateOneStep();  // @BIG5:算中點的力
  for (auto p : particles) {
    p->position() += p->velocity() * (deltaTime / 2);
    p->velocity() += p->acceleration() * (deltaTime / 2);
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = start[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = start[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
"""

# The half-step state is computed into locals and never written back (float division by 2).
MIDPOINT_LOCALS_ONLY = """\
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  // midpoint state
  for (size_t i = 0; i < particles.size(); i++) {
    Eigen::Matrix4Xf xMid = (x0[i] + (x0[i] + v0[i] * deltaTime)) / 2;
    Eigen::Matrix4Xf vMid = (v0[i] + (v0[i] + particles[i]->acceleration() * deltaTime)) / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
"""

MIDPOINT_INTEGER_HALF = """\
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  for (const auto &p : particles) {
    // @BIG5:走半步
    p->position() += p->velocity() * deltaTime * (1 / 2);
    p->velocity() += p->acceleration() * deltaTime * (1 / 2);
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
"""

MIDPOINT_DT_HALVED = """\
  deltaTime /= 2;  // half step
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * (2 * deltaTime);
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * (2 * deltaTime);
  }
"""

MIDPOINT_PER_BODY = """\
  for (size_t b = 0; b < particles.size(); b++) {
    Eigen::Matrix4Xf x0 = particles[b]->position();
    Eigen::Matrix4Xf v0 = particles[b]->velocity();
    particles[b]->position() += particles[b]->velocity() * deltaTime * 0.5f;
    particles[b]->velocity() += particles[b]->acceleration() * deltaTime * 0.5f;
    simulateOneStep();
    particles[b]->position() = x0 + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = v0 + particles[b]->acceleration() * deltaTime;
  }
"""

MIDPOINT_SYMPLECTIC_PREDICTOR = """\
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
    p->position() += p->velocity() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
"""

# RK4 skeleton: {STAGE} builds stage k's state from x0, v0 and kx[k], kv[k]; {FINAL} the result.
RK4_SKELETON = """\
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) { x0.push_back(p->position()); v0.push_back(p->velocity()); }
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  const float h[3] = {0.5f, 0.5f, 1.0f};
  for (int k = 0; k < 4; k++) {
    if (k > 0) simulateOneStep();
    for (size_t i = 0; i < particles.size(); i++) {
      kx[k].push_back(particles[i]->velocity() * deltaTime);
      kv[k].push_back(particles[i]->acceleration() * deltaTime);
    }
    if (k == 3) break;
    for (size_t i = 0; i < particles.size(); i++) {
{STAGE}
    }
  }
  for (size_t i = 0; i < particles.size(); i++) {
{FINAL}
  }
"""
RK4_STAGE = """\
      particles[i]->position() = x0[i] + kx[k][i] * h[k];
      particles[i]->velocity() = v0[i] + kv[k][i] * h[k];"""
RK4_FINAL = """\
    particles[i]->position() = x0[i] + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = v0[i] + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;"""


def rk4(stage=RK4_STAGE, final=RK4_FINAL):
    return RK4_SKELETON.replace("{STAGE}", stage).replace("{FINAL}", final)


RK4_SIXTH_POSITION = rk4(final="""\
    particles[i]->position() = x0[i] + (1 / 6) * (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]);
    particles[i]->velocity() = v0[i] + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6.0f;""")

RK4_SIXTH_BOTH = rk4(final="""\
    // @BIG5:加權平均
    particles[i]->position() = x0[i] + (1 / 6) * (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]);
    particles[i]->velocity() = v0[i] + (1 / 6) * (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]);""")

# x_stage = x0 + dt h (v0 + kv h): the stage position from the new stage velocity.
RK4_STAGE_FROM_NEW_VELOCITY = rk4(stage="""\
      particles[i]->velocity() = v0[i] + kv[k][i] * h[k];
      particles[i]->position() = x0[i] + deltaTime * (v0[i] + kv[k][i] * h[k]) * h[k];""")

RK4_STAGES_DISCARDED = rk4(final="""\
    // TODO weights
    particles[i]->position() = x0[i] + kx[0][i];
    particles[i]->velocity() = v0[i] + kv[0][i];""")

RK4_K4X_IN_VELOCITY = rk4(final="""\
    particles[i]->position() = x0[i] + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = v0[i] + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kx[3][i]) / 6.0f;""")

RK4_EQUAL_WEIGHTS = rk4(final="""\
    particles[i]->position() = x0[i] + (kx[0][i] + kx[1][i] + kx[2][i] + kx[3][i]) / 4.0f;
    particles[i]->velocity() = v0[i] + (kv[0][i] + kv[1][i] + kv[2][i] + kv[3][i]) / 4.0f;""")

RK4_STAGE_FROM_CURRENT = rk4(stage="""\
      if (k == 0) {
        particles[i]->position() = x0[i] + kx[k][i] * h[k];
        particles[i]->velocity() = v0[i] + kv[k][i] * h[k];
      } else {  // keep stepping from where we are
        particles[i]->position() += kx[k][i] * h[k];
        particles[i]->velocity() += kv[k][i] * h[k];
      }""")

RK4_FIRST_BODY = """\
  Particles* p = particles[0];
  Eigen::Matrix4Xf x0 = p->position(), v0 = p->velocity();
  Eigen::Matrix4Xf k1x = p->velocity() * deltaTime, k1v = p->acceleration() * deltaTime;
  p->position() = x0 + k1x * 0.5f;
  p->velocity() = v0 + k1v * 0.5f;
  simulateOneStep();
  Eigen::Matrix4Xf k2x = p->velocity() * deltaTime, k2v = p->acceleration() * deltaTime;
  p->position() = x0 + k2x * 0.5f;
  p->velocity() = v0 + k2v * 0.5f;
  simulateOneStep();
  Eigen::Matrix4Xf k3x = p->velocity() * deltaTime, k3v = p->acceleration() * deltaTime;
  p->position() = x0 + k3x;
  p->velocity() = v0 + k3v;
  simulateOneStep();
  Eigen::Matrix4Xf k4x = p->velocity() * deltaTime, k4v = p->acceleration() * deltaTime;
  p->position() = x0 + (k1x + 2.0f * k2x + 2.0f * k3x + k4x) / 6.0f;
  p->velocity() = v0 + (k1v + 2.0f * k2v + 2.0f * k3v + k4v) / 6.0f;
"""

# One body at a time, each with its own three simulateOneStep() calls.
RK4_PER_BODY = """\
  for (auto p : particles) {
    Eigen::Matrix4Xf x0 = p->position(), v0 = p->velocity();
    Eigen::Matrix4Xf k1x = p->velocity() * deltaTime, k1v = p->acceleration() * deltaTime;
    p->position() = x0 + k1x * 0.5f; p->velocity() = v0 + k1v * 0.5f;
    simulateOneStep();
    Eigen::Matrix4Xf k2x = p->velocity() * deltaTime, k2v = p->acceleration() * deltaTime;
    p->position() = x0 + k2x * 0.5f; p->velocity() = v0 + k2v * 0.5f;
    simulateOneStep();
    Eigen::Matrix4Xf k3x = p->velocity() * deltaTime, k3v = p->acceleration() * deltaTime;
    p->position() = x0 + k3x; p->velocity() = v0 + k3v;
    simulateOneStep();
    Eigen::Matrix4Xf k4x = p->velocity() * deltaTime, k4v = p->acceleration() * deltaTime;
    p->position() = x0 + (k1x + 2.0f * k2x + 2.0f * k3x + k4x) / 6.0f;
    p->velocity() = v0 + (k1v + 2.0f * k2v + 2.0f * k3v + k4v) / 6.0f;
  }
"""

# Code written for the course cloth: after each step the four corners are pinned by index.
PIN_HELPER = """\
namespace {
// keep the corners still (they drift a little otherwise)
void pinCorners(Particles* cloth) {
  const int n = particlesPerEdge;
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) cloth->velocity(corner).setZero();
}
}  // namespace
"""


def pinned(text):
    return text + "  pinCorners(particles[0]);\n"


# ---- The submissions: name -> (edition, big5, {stub: body}, {stub: (causes, also, why)}).
S_SPR, S_FOR = "Cloth::initializeSpring", "Cloth::computeSpringForce"
S_CC, S_SS = "Spheres::collide(Cloth*)", "Spheres::collide()"
S_EX, S_IM = "ExplicitEuler::integrate", "ImplicitEuler::integrate"
S_MI, S_RK = "MidpointEuler::integrate", "RungeKuttaFourth::integrate"


SUBMISSIONS = {
    "2022/big5-shear-aliased-midpoint-first": dict(
        edition="2022", big5=True,
        bodies={S_SPR: SPRINGS_SHEAR_STRUCTURAL, S_IM: IMPLICIT_POINTER_BACKUP,
                S_MI: MIDPOINT_SIMULATE_FIRST, S_SS: sphere_contact("0.8f", SPHERES_NO_APPROACH),
                S_EX: EXPLICIT_STYLED},
        labels={S_SPR: (["shear-rest-length"], [], "shear springs get the structural length"),
                S_IM: (["backup-alias"], [], "auto backup = particles copies the pointers"),
                S_MI: (["no-reevaluation"], [],
                       "simulateOneStep() runs before the half step: forces are never evaluated "
                       "at the midpoint"),
                S_SS: (["no-approach-check"], [], "impulse also for separating pairs")}),
    "2022/float-half-sixth-position-full-velocity": dict(
        edition="2022", big5=False,
        bodies={S_FOR: FORCE_DAMPER_UNNORMALISED, S_RK: RK4_SIXTH_POSITION,
                S_CC: cloth_contact("0.0f", CONTACT_FULL_VELOCITY)},
        labels={S_FOR: (["damper-not-normalised"], [], "damper projected on the raw vector x"),
                S_RK: (["integer-division-rk4"], [],
                       "(1 / 6) on the position update only: the position never moves"),
                S_CC: (["restitution-full-velocity"], [],
                       "impulse from the whole relative velocity: tangential velocity lost")}),
    "2022/safe-auto-swapped-labels-midpoint-locals": dict(
        edition="2022", big5=False,
        bodies={S_SPR: SPRINGS_TYPES_SWAPPED, S_FOR: FORCE_SAFE_AUTO, S_MI: MIDPOINT_LOCALS_ONLY,
                S_CC: cloth_contact("0.0f", CONTACT_FIRST_SPHERE),
                S_SS: sphere_contact("1.0f", spheres())},
        labels={S_SPR: (["swapped-spring-types"], [], "diagonals BEND, distance-2 SHEAR"),
                S_MI: (["no-reevaluation"], [],
                       "the half-step state goes to locals that are never written back, so "
                       "simulateOneStep() sees the start state; `/ 2` is float division here"),
                S_CC: (["first-sphere-only"], [], "i = 0 only"),
                S_SS: (["restitution-ignored"], [], "coefRestitution set to 1")}),
    "2022/hard-coded-assign-accel-stage-velocity": dict(
        edition="2022", big5=False,
        bodies={S_SPR: SPRINGS_HARD_CODED_25, S_FOR: FORCE_ASSIGN,
                S_EX: EXPLICIT_WITH_ACCELERATION, S_RK: RK4_STAGE_FROM_NEW_VELOCITY},
        labels={S_SPR: (["hard-coded-n25"], [], "N = 25 everywhere"),
                S_FOR: (["assign-not-accumulate"], [], "= instead of -= / +="),
                S_EX: (["position-uses-acceleration"], [], "x += v dt + a dt^2 / 2"),
                S_RK: (["rk4-stage-from-wrong-increment"], [],
                       "stage position x0 + dt h (v0 + kv h) uses the new stage velocity, not kx")}),
    "2022/dt-halved-per-body-rk4-mass-formula": dict(
        edition="2022", big5=False,
        bodies={S_MI: MIDPOINT_DT_HALVED, S_RK: RK4_PER_BODY,
                S_CC: cloth_contact("0.0f", CONTACT_MASS_FORMULA),
                S_SS: sphere_contact("0.8f", spheres(j_start="0", guard="\n      if (i == j) continue;"))},
        labels={S_MI: (["deltatime-mutated"], [], "deltaTime /= 2, never restored"),
                S_RK: (["per-body-loop"], [],
                       "each body integrated in its own loop with its own simulateOneStep()"),
                S_CC: (["fixed-particle-massless"], [], "mass formula with mass 0 = massless"),
                S_SS: (["pair-processed-twice"], [], "j from 0: every pair twice")}),
    "2022/ref-backup-discarded-stages-one-end": dict(
        edition="2022", big5=False,
        bodies={S_IM: IMPLICIT_REF_BACKUP, S_RK: RK4_STAGES_DISCARDED, S_FOR: FORCE_ONE_END,
                S_CC: cloth_contact("0.0f", CONTACT_CORRECTION_CLOTH_ONLY)},
        labels={S_IM: (["backup-alias"], [], "auto x0 = position() is an Eigen::Ref"),
                S_RK: (["rk4-stages-discarded"], [], "x = x0 + k1: the stages are thrown away"),
                S_FOR: (["force-one-end-only"], [], "only the start particle gets the force"),
                S_CC: (["correction-one-body"], [], "only the cloth particle is pushed out")}),
    "2022/first-body-everywhere-one-diagonal": dict(
        edition="2022", big5=False,
        bodies={S_EX: EXPLICIT_FIRST_BODY, S_RK: RK4_FIRST_BODY, S_SPR: SPRINGS_ONE_DIAGONAL,
                S_SS: sphere_contact("0.8f", spheres(correct_j="// sphere j stays"))},
        labels={S_EX: (["only-first-body"], [], "particles[0] only"),
                S_RK: (["only-first-body"], [], "particles[0] only"),
                S_SPR: (["missing-springs"], [], "no down-left shear springs"),
                S_SS: (["correction-one-body"], [], "only sphere i is pushed")}),
    "2022/big5-k4x-hooke-sign-symplectic-predictor": dict(
        edition="2022", big5=True,
        bodies={S_RK: RK4_K4X_IN_VELOCITY, S_IM: IMPLICIT_SYMPLECTIC_PREDICTOR,
                S_FOR: FORCE_HOOKE_SIGN, S_CC: cloth_contact("0.0f", CONTACT_NO_APPROACH)},
        labels={S_RK: (["rk4-mixed-increments"], [], "k4's position increment in the velocity"),
                S_FOR: (["spring-force-sign"], [], "(rest - length)"),
                S_CC: (["no-approach-check"], [], "impulse for separating pairs")}),
    "2022/symplectic-both-sqrt2-normal-stage-current": dict(
        edition="2022", big5=False,
        bodies={S_EX: EXPLICIT_SYMPLECTIC, S_MI: MIDPOINT_SYMPLECTIC_PREDICTOR,
                S_SPR: SPRINGS_SQRT2, S_CC: cloth_contact("0.0f", CONTACT_NORMAL_REVERSED),
                S_RK: RK4_STAGE_FROM_CURRENT},
        labels={S_SPR: (["approximate-sqrt2"], [], "shear length 1.41 * side"),
                S_CC: (["collision-normal-sign"], [], "normal from the particle to the sphere"),
                S_RK: (["rk4-stage-not-from-backup"], [], "stages 2 and 3 step from the current state")}),
    "2024/big5-shear-full-velocity-integer-half-per-body": dict(
        edition="2024", big5=True,
        bodies={S_SPR: SPRINGS_SHEAR_STRUCTURAL, S_CC: cloth_contact("0.0f", CONTACT_FULL_VELOCITY),
                S_MI: MIDPOINT_INTEGER_HALF, S_IM: IMPLICIT_PER_BODY},
        labels={S_SPR: (["shear-rest-length"], [], "structural length for shear"),
                S_CC: (["restitution-full-velocity"], [], "whole relative velocity"),
                S_MI: (["integer-division-half"], [], "deltaTime * (1 / 2) is zero"),
                S_IM: (["per-body-loop"], [], "one body at a time, each with simulateOneStep()")}),
    "2024/dangling-auto-sixth-touching": dict(
        edition="2024", big5=False,
        bodies={S_FOR: FORCE_DANGLING_AUTO, S_RK: RK4_SIXTH_BOTH,
                S_CC: cloth_contact("0.0f", CONTACT_TOUCHING_SKIPPED)},
        labels={S_FOR: (["dangling-auto-expression"], ["crashed", "non-finite"],
                        "auto holds position(s) - position(e) over two temporary Refs"),
                S_RK: (["integer-division-rk4"], [], "(1 / 6) on both updates: nothing moves"),
                S_CC: (["touching-skipped"], [], "dist >= r skipped")}),
    "2024/swapped-damper-sign-per-body-midpoint": dict(
        edition="2024", big5=False,
        bodies={S_SPR: SPRINGS_TYPES_SWAPPED, S_FOR: FORCE_DAMPER_SIGN, S_MI: MIDPOINT_PER_BODY,
                S_EX: EXPLICIT_STYLED, S_CC: cloth_contact("0.0f", CONTACT_CORRECT_STYLED)},
        labels={S_SPR: (["swapped-spring-types"], [], "labels swapped"),
                S_FOR: (["damper-sign"], [], "relative velocity v_e - v_s"),
                S_MI: (["per-body-loop"], [], "one body at a time")}),
    "2024/no-simulate-equal-weights-restitution-one": dict(
        edition="2024", big5=False,
        bodies={S_IM: IMPLICIT_NO_SIMULATE, S_RK: RK4_EQUAL_WEIGHTS,
                S_CC: cloth_contact("1.0f", CONTACT_CORRECT_STYLED), S_FOR: FORCE_DIVIDE_BY_MASS},
        labels={S_IM: (["no-reevaluation"], [], "simulateOneStep() never called"),
                S_RK: (["rk4-wrong-weights"], [], "(k1 + k2 + k3 + k4) / 4"),
                S_CC: (["restitution-ignored"], [], "coefRestitution overwritten with 1"),
                S_FOR: (["fixed-particle-moves"], ["non-finite"], "F / mass: the corners get inf")}),
    "2024/course-cloth-pins-bend-correction": dict(
        edition="2024", big5=False, integrator_prefix=PIN_HELPER,
        bodies={S_EX: pinned(body("2024", S_EX)), S_IM: pinned(body("2024", S_IM)),
                S_MI: pinned(body("2024", S_MI)), S_RK: pinned(body("2024", S_RK)),
                S_SPR: SPRINGS_BEND_STRUCTURAL,
                S_CC: cloth_contact("0.0f", CONTACT_CORRECTION_CLOTH_ONLY)},
        labels={S_SPR: (["bend-rest-length"], [], "bend springs get the structural length"),
                S_CC: (["correction-one-body"], [], "only the cloth particle is pushed out"),
                **{stub: (["integrator-pins-particles"], [],
                          "the corners re-pinned by index: the 2024 program's keys 1-4 unpin "
                          "them, and the stub holds them still again")
                   for stub in (S_EX, S_IM, S_MI, S_RK)}}),
}


def write_submission(name, spec):
    edition = spec["edition"]
    files = dict(base.reference(edition))
    for stub, text in spec["bodies"].items():
        file = base.STUB_HEAD[stub][0]
        if stub == S_SPR:
            files[file] = base.keep_gl_tail(files[file], text)
        else:
            files[file] = base.replace_body(files[file], stub, text)
    if "integrator_prefix" in spec:
        files["integrator.cpp"] = files["integrator.cpp"].replace(
            '#include "configs.h"\n', '#include "configs.h"\n\n' + spec["integrator_prefix"], 1)
    out = HERE / name
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    for file, text in files.items():
        data = base.big5_comments(text) if spec["big5"] else base.utf8_comments(text)
        (out / file).write_bytes(data)
    stubs = base.STUBS[edition]
    labels = {"edition": edition, "big5_comments": spec["big5"], "stubs": {}}
    for stub in stubs:
        if stub in spec["labels"]:
            causes, also, why = spec["labels"][stub]
            labels["stubs"][stub] = {"verdict": "loses", "causes": causes, "also": also,
                                     "why": why}
        else:
            labels["stubs"][stub] = {"verdict": "full"}
    (out / "labels.json").write_text(json.dumps(labels, indent=1) + "\n")


def main():
    for name, spec in SUBMISSIONS.items():
        write_submission(name, spec)
    print(f"make_corpus: wrote {len(SUBMISSIONS)} submissions")


if __name__ == "__main__":
    main()
