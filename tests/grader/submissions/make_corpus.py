#!/usr/bin/env python3
"""Writes the grader's test corpus (tests/grader/submissions/) from the course-form reference files
(tools/grader/reference/<edition>/): the correct submissions and the mutants, each with its
expected.json. Run from anywhere: python3 tests/grader/submissions/make_corpus.py

Every mutant is one realistic mistake: a textual edit inside one function of one reference file,
and the edit must match exactly as often as stated, so a reference change that breaks a mutant
fails here instead of silently producing a correct "mutant". A mutant directory holds only the
changed file; "base" in its expected.json names the submission that supplies the other two files.
--full writes all three files into every mutant directory instead (no "base").
"""
import json
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
REFERENCE = "tools/grader/reference"

STUBS = {
    "2022": ["Cloth::initializeSpring", "Cloth::computeSpringForce", "Spheres::collide(Cloth*)",
             "Spheres::collide()", "ExplicitEuler::integrate", "ImplicitEuler::integrate",
             "MidpointEuler::integrate", "RungeKuttaFourth::integrate"],
}
STUBS["2024"] = [s for s in STUBS["2022"] if s != "Spheres::collide()"]

# The definition that opens each stub in the course files, and the file it lives in.
STUB_HEAD = {
    "Cloth::initializeSpring": ("cloth.cpp", "void Cloth::initializeSpring() {"),
    "Cloth::computeSpringForce": ("cloth.cpp", "void Cloth::computeSpringForce() {"),
    "Spheres::collide(Cloth*)": ("sphere.cpp", "void Spheres::collide(Cloth* cloth) {"),
    "Spheres::collide()": ("sphere.cpp", "void Spheres::collide() {"),
    "ExplicitEuler::integrate": ("integrator.cpp", "void ExplicitEuler::integrate("),
    "ImplicitEuler::integrate": ("integrator.cpp", "void ImplicitEuler::integrate("),
    "MidpointEuler::integrate": ("integrator.cpp", "void MidpointEuler::integrate("),
    "RungeKuttaFourth::integrate": ("integrator.cpp", "void RungeKuttaFourth::integrate("),
}
FILES = ["cloth.cpp", "sphere.cpp", "integrator.cpp"]


def function_span(text, stub):
    """(start, end) of the body of `stub` in `text`: from after its opening brace to its closing
    brace (a '}' alone at the start of a line, the course files' layout)."""
    head = STUB_HEAD[stub][1]
    at = text.index(head)
    assert text.count(head) == 1, head
    open_brace = text.index("{\n", at) + 2
    close = text.index("\n}\n", open_brace) + 1
    return open_brace, close


def edit(text, stub, pairs):
    """Applies (old, new[, count]) replacements inside `stub`'s body only; each `old` must occur
    exactly `count` times (default 1) there."""
    start, end = function_span(text, stub)
    body = text[start:end]
    for pair in pairs:
        old, new = pair[0], pair[1]
        count = pair[2] if len(pair) > 2 else 1
        found = body.count(old)
        if found != count:
            sys.exit(f"make_corpus: {stub}: expected {count} x {old!r}, found {found}")
        body = body.replace(old, new)
    return text[:start] + body + text[end:]


def replace_body(text, stub, body):
    start, end = function_span(text, stub)
    return text[:start] + body + text[end:]


def reference(edition):
    return {f: (ROOT / REFERENCE / edition / f).read_text() for f in FILES}


def write_expected(directory, edition, kind, description, losing=(), diagnoses=(), **extra):
    for stub in losing:
        assert stub in STUBS[edition], (directory, stub)
    expected = {"edition": edition, "kind": kind, "description": description}
    expected.update(extra)
    expected["stubs_losing_points"] = list(losing)
    expected["diagnoses"] = list(diagnoses)
    directory.mkdir(parents=True, exist_ok=True)
    (directory / "expected.json").write_text(json.dumps(expected, indent=2) + "\n")


# ------------------------------------------------------------------------------------------------
# Stub bodies of the correct student-style submissions (same semantics, other shapes).

ZIP_SPRINGS = """\
  // TODO: Connect particles with springs.
  // Here is a simple example which connects the horizontal structural springs.
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // @BIG5:彈簧：結構、剪切、彎曲，每個質點只連右邊與下面
  float shearLength = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();
  float bendLength = (_particles.position(0) - _particles.position(2)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      bool hasDown = i + 1 < particlesPerEdge;
      if (hasDown) _springs.emplace_back(index, index + particlesPerEdge, structrualLength, Spring::Type::STRUCTURAL);
      if (hasDown && j + 1 < particlesPerEdge)
        _springs.emplace_back(index, index + particlesPerEdge + 1, shearLength, Spring::Type::SHEAR);
      if (hasDown && j > 0) _springs.emplace_back(index, index + particlesPerEdge - 1, shearLength, Spring::Type::SHEAR);
      if (j + 2 < particlesPerEdge) _springs.emplace_back(index, index + 2, bendLength, Spring::Type::BEND);
      if (i + 2 < particlesPerEdge)
        _springs.emplace_back(index, index + 2 * particlesPerEdge, bendLength, Spring::Type::BEND);
    }
  }
"""

ZIP_FORCES = """\
  for (const auto& spring : _springs) {
    int a = spring.startParticleIndex(), b = spring.endParticleIndex();
    Eigen::Vector4f delta = _particles.position(a) - _particles.position(b);
    float length = delta.norm();
    Eigen::Vector4f unit = delta.normalized();
    Eigen::Vector4f relativeVelocity = _particles.velocity(a) - _particles.velocity(b);
    // Hooke + damper, both along the spring; this is the force on a, b gets the opposite.
    Eigen::Vector4f springForce = -springCoef * (length - spring.length()) * unit;
    Eigen::Vector4f damperForce = -damperCoef * relativeVelocity.dot(unit) * unit;
    Eigen::Vector4f force = springForce + damperForce;
    _particles.acceleration(a) += force * _particles.inverseMass(a);
    _particles.acceleration(b) -= force * _particles.inverseMass(b);
  }
"""

ZIP_COLLIDE_CLOTH = """\
  constexpr float coefRestitution = 0.0f;
  // @BIG5:碰撞：球與布料的質點，這裡用老師給的公式
  Particles& cp = cloth->particles();
  for (int s = 0; s < sphereCount; ++s) {
    for (int k = 0; k < particlesPerEdge * particlesPerEdge; ++k) {
      Eigen::Vector4f diff = _particles.position(s) - cp.position(k);
      float distance = diff.norm();
      if (distance > _radius[s]) continue;
      float penetration = _radius[s] - distance;
      Eigen::Vector4f normal = diff.normalized();
      float vn = (_particles.velocity(s) - cp.velocity(k)).dot(normal);
      if (vn < 0.0f) {
        float j = -(1.0f + coefRestitution) * vn / (_particles.inverseMass(s) + cp.inverseMass(k));
        _particles.velocity(s) += j * _particles.inverseMass(s) * normal;
        cp.velocity(k) -= j * cp.inverseMass(k) * normal;
      }
      _particles.position(s) += 0.15f * penetration * normal;
      cp.position(k) -= 0.15f * penetration * normal;
    }
  }
"""

ZIP_COLLIDE_SPHERES = """\
  constexpr float coefRestitution = 0.8f;
  for (int a = 0; a < sphereCount; ++a) {
    for (int b = a + 1; b < sphereCount; ++b) {
      Eigen::Vector4f diff = _particles.position(a) - _particles.position(b);
      float distance = diff.norm();
      float minDistance = _radius[a] + _radius[b];
      if (distance > minDistance) continue;
      float penetration = minDistance - distance;
      Eigen::Vector4f normal = diff.normalized();
      float vn = (_particles.velocity(a) - _particles.velocity(b)).dot(normal);
      if (vn < 0.0f) {
        float j = -(1.0f + coefRestitution) * vn / (_particles.inverseMass(a) + _particles.inverseMass(b));
        _particles.velocity(a) += j * _particles.inverseMass(a) * normal;
        _particles.velocity(b) -= j * _particles.inverseMass(b) * normal;
      }
      _particles.position(a) += 0.15f * penetration * normal;
      _particles.position(b) -= 0.15f * penetration * normal;
    }
  }
"""

ZIP_EXPLICIT = """\
  // @BIG5:積分器
  for (Particles* p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
"""


def zip_predict_correct(half):
    scale = " * 0.5f" if half else ""
    return f"""\
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n);
  for (size_t i = 0; i < n; ++i) {{
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    particles[i]->position() += particles[i]->velocity() * deltaTime{scale};
    particles[i]->velocity() += particles[i]->acceleration() * deltaTime{scale};
  }}
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {{
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }}
"""


ZIP_RK4 = """\
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n), sumX(n), sumV(n);
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
  }
  const float stageScale[3] = {0.5f, 0.5f, 1.0f};
  const float weight[4] = {1.0f, 2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (size_t i = 0; i < n; ++i) {
      Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime;
      Eigen::Matrix4Xf kv = particles[i]->acceleration() * deltaTime;
      if (stage == 0) {
        sumX[i] = kx;
        sumV[i] = kv;
      } else {
        sumX[i] += weight[stage] * kx;
        sumV[i] += weight[stage] * kv;
      }
      if (stage < 3) {
        particles[i]->position() = x0[i] + kx * stageScale[stage];
        particles[i]->velocity() = v0[i] + kv * stageScale[stage];
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + sumX[i] / 6.0f;
    particles[i]->velocity() = v0[i] + sumV[i] / 6.0f;
  }
"""

# Accepted variants: symplectic explicit, implicit corrector with v_new, springs in another order
# with the larger index first.
VARIANT_SPRINGS = """\
  float structrualLength = (_particles.position(0) - _particles.position(1)).norm();
  for (int i = 0; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + 1, structrualLength, Spring::Type::STRUCTURAL);
    }
  }
  // Bend first, then shear, then the vertical structural springs; lower particle first.
  float bendLength = (_particles.position(0) - _particles.position(2)).norm();
  for (int i = 0; i < particlesPerEdge - 2; ++i)
    for (int j = 0; j < particlesPerEdge; ++j)
      _springs.emplace_back((i + 2) * particlesPerEdge + j, i * particlesPerEdge + j, bendLength, Spring::Type::BEND);
  for (int i = 0; i < particlesPerEdge; ++i)
    for (int j = 2; j < particlesPerEdge; ++j)
      _springs.emplace_back(i * particlesPerEdge + j, i * particlesPerEdge + j - 2, bendLength, Spring::Type::BEND);
  float shearLength = (_particles.position(1) - _particles.position(particlesPerEdge)).norm();
  for (int i = 1; i < particlesPerEdge; ++i) {
    for (int j = 0; j < particlesPerEdge - 1; ++j) {
      // (i, j) to the upper-right (i - 1, j + 1) and the upper-left (i - 1, j - 1)
      _springs.emplace_back(i * particlesPerEdge + j, (i - 1) * particlesPerEdge + j + 1, shearLength, Spring::Type::SHEAR);
    }
    for (int j = 1; j < particlesPerEdge; ++j) {
      _springs.emplace_back(i * particlesPerEdge + j, (i - 1) * particlesPerEdge + j - 1, shearLength, Spring::Type::SHEAR);
    }
  }
  for (int i = 1; i < particlesPerEdge; ++i)
    for (int j = 0; j < particlesPerEdge; ++j)
      _springs.emplace_back(i * particlesPerEdge + j, (i - 1) * particlesPerEdge + j, structrualLength, Spring::Type::STRUCTURAL);

"""

VARIANT_EXPLICIT = """\
  // Velocity first, then the position with the new velocity (symplectic Euler).
  for (const auto &p : particles) {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
"""

VARIANT_IMPLICIT = """\
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  // v_{n+1} first, then x_{n+1} = x_n + v_{n+1} dt.
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
  }
"""


def keep_gl_tail(text, body):
    """initializeSpring bodies above replace only the spring pushes: keep the GL tail."""
    start, end = function_span(text, "Cloth::initializeSpring")
    tail = text[start:end]
    marker = tail.index("  std::vector<GLuint> structrualIndices")
    if "  // DO NOT MODIFY BELOW THIS LINE\n" in tail:
        marker = tail.index("  // DO NOT MODIFY BELOW THIS LINE\n")
    return text[:start] + body + tail[marker:] + text[end:]


def big5_comments(text):
    """'// @BIG5:words' becomes a Big5-encoded comment; returns bytes."""
    out = []
    for line in text.split("\n"):
        if "// @BIG5:" in line:
            indent, words = line.split("// @BIG5:")
            encoded = words.encode("big5")
            # a 0x5C trail byte at the end of a // comment would splice the next line
            assert b"\\" not in encoded, words
            out.append(indent.encode() + b"// " + encoded)
        else:
            out.append(line.encode("ascii"))
    return b"\n".join(out)


def utf8_comments(text):
    return text.replace("// @BIG5:", "// ").encode("utf-8")


def crlf(data):
    return data.replace(b"\n", b"\r\n")


BOM = b"\xef\xbb\xbf"

STUDENT_MAIN = """\
#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include "cloth.h"
#include "configs.h"
#include "integrator.h"
#include "sphere.h"

// The course's main.cpp (window, GUI, render loop) is part of every hand-in; the grader ignores it.
int main() {
  if (!glfwInit()) return 1;
  return 0;
}
"""

STUDENT_CONFIGS_H = """\
#pragma once
#include <Eigen/Core>
// Changed by the student: a comment and a larger default step. Student headers are never used.
inline constexpr int particlesPerEdge = 25;
inline constexpr int clothWidth = 2;
inline constexpr int clothHeight = 2;
inline constexpr float particleMass = 1.0f;
inline constexpr float sphereDensity = 1e3f;
inline constexpr float baseSpeed = 1e-3f;
inline constexpr int sphereSlice = 36;
inline constexpr int sphereStack = 18;
extern float deltaTime;
extern float springCoef;
extern float damperCoef;
extern float viscousCoef;
"""


def zip_files(edition):
    ref = reference(edition)
    cloth = keep_gl_tail(ref["cloth.cpp"], ZIP_SPRINGS)
    cloth = replace_body(cloth, "Cloth::computeSpringForce", ZIP_FORCES)
    sphere = replace_body(ref["sphere.cpp"], "Spheres::collide(Cloth*)", ZIP_COLLIDE_CLOTH)
    if edition == "2022":
        sphere = replace_body(sphere, "Spheres::collide()", ZIP_COLLIDE_SPHERES)
    integrator = replace_body(ref["integrator.cpp"], "ExplicitEuler::integrate", ZIP_EXPLICIT)
    integrator = replace_body(integrator, "ImplicitEuler::integrate", zip_predict_correct(False))
    integrator = replace_body(integrator, "MidpointEuler::integrate", zip_predict_correct(True))
    integrator = replace_body(integrator, "RungeKuttaFourth::integrate", ZIP_RK4)
    header = "// HW1, student 0812345. Based on the course template.\n"
    return tuple(header + strip_header(text) for text in (cloth, sphere, integrator))


def strip_header(text):
    """Drops the reference's leading comment block (a student's file has its own)."""
    lines = text.split("\n")
    while lines[0].startswith("//"):
        lines.pop(0)
    return "\n".join(lines)


def write_zip_submission(edition):
    """A hand-in as it arrives: a folder per student with src/ and include/, CRLF, a BOM, Big5
    comments, the student's own (changed) headers, main.cpp, and a stale copy outside src/."""
    cloth, sphere, integrator = zip_files(edition)
    name = "student-zip"
    top = HERE / edition / name / ("HW1_0812345" if edition == "2022" else "HW1_0812345/HW1")
    src, include = top / "src", top / "include"
    src.mkdir(parents=True, exist_ok=True)
    include.mkdir(parents=True, exist_ok=True)
    if edition == "2022":
        (src / "cloth.cpp").write_bytes(BOM + crlf(utf8_comments(cloth)))
        (src / "sphere.cpp").write_bytes(big5_comments(sphere))
        (src / "integrator.cpp").write_bytes(crlf(big5_comments(integrator)))
    else:
        (src / "cloth.cpp").write_bytes(crlf(big5_comments(cloth)))
        (src / "sphere.cpp").write_bytes(BOM + utf8_comments(sphere))
        (src / "integrator.cpp").write_bytes(BOM + crlf(utf8_comments(integrator)))
    (src / "main.cpp").write_text(STUDENT_MAIN)
    (include / "configs.h").write_text(STUDENT_CONFIGS_H)
    # an older draft kept outside src/: the grader must prefer src/
    stale = top / "old"
    stale.mkdir(exist_ok=True)
    (stale / "cloth.cpp").write_text("// first draft, does not compile\n#include \"cloth.h\"\nvoid Cloth::computeSpringForce() { oops }\n")
    prefix = top.relative_to(HERE / edition / name).as_posix()
    write_expected(HERE / edition / name, edition, "correct",
                   "hand-in folder with src/ and changed include/, CRLF, BOM, Big5 comments, main.cpp, "
                   "a stale old/cloth.cpp; springs pushed interleaved in one loop; scalar impulse; "
                   "Matrix4Xf backups; RK4 in one stage loop",
                   files_used={f: f"{prefix}/src/{f}" for f in FILES})


def write_variants_submission(edition):
    ref = reference(edition)
    cloth = keep_gl_tail(ref["cloth.cpp"], VARIANT_SPRINGS)
    integrator = replace_body(ref["integrator.cpp"], "ExplicitEuler::integrate", VARIANT_EXPLICIT)
    integrator = replace_body(integrator, "ImplicitEuler::integrate", VARIANT_IMPLICIT)
    label = "// Grader corpus submission `accepted-variants`: {} in the accepted variant form.\n"
    cloth = label.format("initializeSpring") + strip_header(cloth)
    integrator = label.format("ExplicitEuler and ImplicitEuler") + strip_header(integrator)
    directory = HERE / edition / "accepted-variants"
    (directory / "src").mkdir(parents=True, exist_ok=True)
    (directory / "src" / "cloth.cpp").write_text(cloth)
    (directory / "src" / "sphere.cpp").write_text(ref["sphere.cpp"])
    (directory / "src" / "integrator.cpp").write_text(integrator)
    write_expected(directory, edition, "correct",
                   "accepted variants: explicit written as symplectic Euler, implicit corrector with "
                   "v_new, springs in another type order with the larger index first")


def write_reference_submission(edition):
    directory = HERE / edition / "reference"
    (directory / "src").mkdir(parents=True, exist_ok=True)
    for f, text in reference(edition).items():
        (directory / "src" / f).write_text(text)
    write_expected(directory, edition, "correct",
                   f"the reference solution in course form ({REFERENCE}/{edition}), copied as a hand-in")


# ------------------------------------------------------------------------------------------------
# Mutants: (name, editions, stub, edits or ("body", text), diagnoses, description)

S = "Cloth::initializeSpring"
F = "Cloth::computeSpringForce"
C = "Spheres::collide(Cloth*)"
P = "Spheres::collide()"
E = "ExplicitEuler::integrate"
I = "ImplicitEuler::integrate"
M = "MidpointEuler::integrate"
R = "RungeKuttaFourth::integrate"
BOTH = ("2022", "2024")
ONLY22 = ("2022",)

SHEAR_LENGTH = "float shearLength = (_particles.position(0) - _particles.position(particlesPerEdge + 1)).norm();"
BEND_LENGTH = "float bendLength = (_particles.position(0) - _particles.position(2)).norm();"
DOWN_LEFT = """\
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 1; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + particlesPerEdge - 1, shearLength, Spring::Type::SHEAR);
    }
  }
"""
VERTICAL_HEAD = """\
  for (int i = 0; i < particlesPerEdge - 1; ++i) {
    for (int j = 0; j < particlesPerEdge; ++j) {
      int index = i * particlesPerEdge + j;
      _springs.emplace_back(index, index + particlesPerEdge, structrualLength"""
FORCE_EXPR = "direction * (damperCoef * relativeVelocity.dot(direction) + springCoef * (length - spring.length()))"
A_START = "_particles.acceleration(start) -= force * _particles.inverseMass(start);"
A_END = "_particles.acceleration(end) += force * _particles.inverseMass(end);"
IMPULSE_CLOTH = """\
        Eigen::Vector4f impulse = (-(1 + coefRestitution) * normalVelocity) /
                                  (clothParticles.inverseMass(j) + _particles.inverseMass(i));"""
FIXED_MASSLESS = """\
      if (approach < 0) {
        // The restitution formula from the spec, with the masses.
        float massSphere = _particles.mass(i);
        float massCloth = clothParticles.mass(j);
        float uSphere = _particles.velocity(i).dot(normal);
        float uCloth = clothParticles.velocity(j).dot(normal);
        float newSphere = (massSphere * uSphere + massCloth * uCloth + massCloth * coefRestitution * (uCloth - uSphere)) /
                          (massSphere + massCloth);
        float newCloth = (massSphere * uSphere + massCloth * uCloth + massSphere * coefRestitution * (uSphere - uCloth)) /
                         (massSphere + massCloth);
        _particles.velocity(i) += (newSphere - uSphere) * normal;
        clothParticles.velocity(j) += (newCloth - uCloth) * normal;
      }
"""
IMPULSE_BLOCK_CLOTH = """\
      if (approach < 0) {
        Eigen::Vector4f normalVelocity = normal * approach;
""" + IMPULSE_CLOTH + """
        _particles.velocity(i) += impulse * _particles.inverseMass(i);
        clothParticles.velocity(j) -= impulse * clothParticles.inverseMass(j);
      }
"""
APPROACH_COMMENT = "      // Only approaching pairs get an impulse; a fixed particle (inverse mass 0) does not move.\n"
BACKUP_COMMENT = "  // A pointer-vector copy would alias the live state: back up the Particles themselves.\n"
CORRECTION_COMMENT = "      // Push them apart to prevent penetration (ignores mass, as the course's hint does).\n"
PREDICT_FULL = """\
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
"""
PREDICT_HALF = """\
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
"""
BACKUP = """\
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
"""
CORRECT = """\
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
"""
MIDPOINT_REF_BACKUP = """\
  // particles[0] is the cloth, particles[1] the spheres.
  auto clothPosition = particles[0]->position();
  auto clothVelocity = particles[0]->velocity();
  auto spherePosition = particles[1]->position();
  auto sphereVelocity = particles[1]->velocity();
""" + PREDICT_HALF + """\
  simulateOneStep();
  particles[0]->position() = clothPosition + particles[0]->velocity() * deltaTime;
  particles[0]->velocity() = clothVelocity + particles[0]->acceleration() * deltaTime;
  particles[1]->position() = spherePosition + particles[1]->velocity() * deltaTime;
  particles[1]->velocity() = sphereVelocity + particles[1]->acceleration() * deltaTime;
"""
FINAL_X = "(k1x[i] + 2.0f * k2x[i] + 2.0f * k3x[i] + k4x[i]) / 6.0f"
FINAL_V = "(k1v[i] + 2.0f * k2v[i] + 2.0f * k3v[i] + k4v[i]) / 6.0f"
LOOP_ALL = "for (size_t i = 0; i < particles.size(); ++i) {"

MUTANTS = [
    # Cloth::initializeSpring
    ("spring-shear-structural-length", BOTH, S, [(SHEAR_LENGTH, "float shearLength = structrualLength;")],
     ["shear-rest-length"], "shear springs get the structural rest length 1/6"),
    ("spring-shear-approximate-sqrt2", ONLY22, S,
     [(SHEAR_LENGTH, "float shearLength = structrualLength * 1.41f;")],
     ["approximate-sqrt2"], "shear rest length as structural * 1.41f instead of measured"),
    ("spring-bend-structural-length", ONLY22, S, [(BEND_LENGTH, "float bendLength = structrualLength;")],
     ["bend-rest-length"], "bend springs get the structural rest length"),
    ("spring-types-swapped", ONLY22, S,
     [("shearLength, Spring::Type::SHEAR", "shearLength, Spring::Type::@", 2),
      ("bendLength, Spring::Type::BEND", "bendLength, Spring::Type::SHEAR", 2),
      ("Spring::Type::@", "Spring::Type::BEND", 2)],
     ["swapped-spring-types"], "shear springs labelled BEND and bend springs labelled SHEAR"),
    ("spring-hard-coded-25", BOTH, S,
     [("index + particlesPerEdge, ", "index + 25, "),
      ("index + particlesPerEdge + 1", "index + 26"),
      ("index + particlesPerEdge - 1", "index + 24"),
      ("index + 2 * particlesPerEdge", "index + 50")],
     ["hard-coded-n25"], "neighbour offsets hard-coded as 25, 26, 24, 50"),
    ("spring-missing-shear-diagonal", ONLY22, S, [(DOWN_LEFT, "")],
     ["missing-springs"], "the down-left shear pass is missing (576 shear springs, not 1152)"),
    ("spring-duplicate-structural", ONLY22, S,
     [(VERTICAL_HEAD + ", Spring::Type::STRUCTURAL);\n",
       VERTICAL_HEAD + ", Spring::Type::STRUCTURAL);\n"
       "      if (j > 0) _springs.emplace_back(index, index - 1, structrualLength, Spring::Type::STRUCTURAL);\n")],
     ["duplicate-springs"], "each particle also connects to its left neighbour: horizontal structural springs twice"),
    ("spring-vertical-off-by-one", ONLY22, S,
     [(VERTICAL_HEAD, VERTICAL_HEAD.replace("i < particlesPerEdge - 1", "i < particlesPerEdge"))],
     ["wrong-spring-endpoints"], "vertical structural loop runs one row too far: end index past the last particle"),
    # Cloth::computeSpringForce
    ("force-assign", BOTH, F,
     [(A_START, "_particles.acceleration(start) = -force * _particles.inverseMass(start);"),
      (A_END, "_particles.acceleration(end) = force * _particles.inverseMass(end);")],
     ["assign-not-accumulate"], "accelerations assigned with = instead of -= / +="),
    ("force-ends-swapped", ONLY22, F,
     [(A_START, "_particles.acceleration(start) += force * _particles.inverseMass(start);"),
      (A_END, "_particles.acceleration(end) -= force * _particles.inverseMass(end);")],
     ["spring-force-sign"], "+= and -= swapped: the whole spring force has the wrong sign"),
    ("force-hooke-sign", ONLY22, F, [("(length - spring.length())", "(spring.length() - length)")],
     ["spring-force-sign"], "Hooke term (rest - length) instead of (length - rest)"),
    ("force-damper-sign", ONLY22, F,
     [("Eigen::Vector4f relativeVelocity = _particles.velocity(start) - _particles.velocity(end);",
       "Eigen::Vector4f relativeVelocity = _particles.velocity(end) - _particles.velocity(start);")],
     ["damper-sign"], "relative velocity taken as v_end - v_start: the damper pushes"),
    ("force-damper-not-normalised", ONLY22, F,
     [("    direction.normalize();\n    Eigen::Vector4f relativeVelocity = _particles.velocity(start) - _particles.velocity(end);\n",
       "    Eigen::Vector4f relativeVelocity = _particles.velocity(start) - _particles.velocity(end);\n"
       "    float damping = damperCoef * relativeVelocity.dot(direction);\n    direction.normalize();\n"),
      ("damperCoef * relativeVelocity.dot(direction) + springCoef", "damping + springCoef")],
     ["damper-not-normalised"], "damper projected on the spring vector before it is normalised"),
    ("force-no-damper", ONLY22, F, [(FORCE_EXPR, "direction * (springCoef * (length - spring.length()))")],
     ["missing-damper"], "no damper term"),
    ("force-one-end-only", ONLY22, F, [("    " + A_END + "\n", "")],
     ["force-one-end-only"], "only the start particle gets the spring force"),
    ("force-divide-by-mass", ONLY22, F,
     [("force * _particles.inverseMass(start)", "force / _particles.mass(start)"),
      ("force * _particles.inverseMass(end)", "force / _particles.mass(end)")],
     ["fixed-particle-moves"], "F / mass(i) instead of F * inverseMass(i): fixed particles get inf"),
    ("force-dangling-auto", ONLY22, F,
     [("Eigen::Vector4f relativeVelocity = _particles.velocity(start) - _particles.velocity(end);",
       "auto relativeVelocity = _particles.velocity(start) - _particles.velocity(end);")],
     ["dangling-auto-expression"],  # its crash is that cause's doing: 'crashed' is left out beside it
     "auto holds an Eigen expression over two Ref temporaries (undefined behaviour; segfaults with g++ 12 -O1 and -O2)"),
    # Spheres::collide(Cloth*)
    ("cloth-no-approach-check", BOTH, C, [(APPROACH_COMMENT, ""), ("      if (approach < 0) {\n", "      {\n")],
     ["no-approach-check"], "impulse applied even when the pair already separates"),
    ("cloth-restitution-full-velocity", ONLY22, C,
     [("Eigen::Vector4f normalVelocity = normal * approach;", "Eigen::Vector4f normalVelocity = relativeVelocity;")],
     ["restitution-full-velocity"], "impulse from the full relative velocity: tangential velocity changes too"),
    ("cloth-first-sphere-only", BOTH, C,
     [("_particles.position(i)", "_particles.position(0)", 2), ("_particles.velocity(i)", "_particles.velocity(0)", 2),
      ("_radius[i]", "_radius[0]"), ("_particles.inverseMass(i)", "_particles.inverseMass(0)", 2)],
     ["first-sphere-only"], "every contact computed with sphere 0 (position(0), _radius[0])"),
    ("cloth-fixed-particle-massless", BOTH, C, [(APPROACH_COMMENT, ""), (IMPULSE_BLOCK_CLOTH, FIXED_MASSLESS)],
     ["fixed-particle-massless"], "the spec's mass formula: a fixed particle (mass 0) acts massless"),
    ("cloth-fixed-particle-skipped", BOTH, C,
     [("      // Cloth particles have radius 0: they touch when inside the sphere.\n",
       "      // A pinned corner cannot move: leave it alone.\n"
       "      if (clothParticles.mass(j) == 0.0f) continue;\n"
       "      // Cloth particles have radius 0: they touch when inside the sphere.\n")],
     ["fixed-particle-skipped"], "a fixed particle (mass 0) skipped: the sphere passes through a pinned corner"),
    ("cloth-correction-one-body", ONLY22, C, [("      _particles.position(i) += correction;\n", "")],
     ["correction-one-body"], "position correction applied to the cloth particle only"),
    ("cloth-no-correction", ONLY22, C,
     [(CORRECTION_COMMENT, ""),
      ("      _particles.position(i) += correction;\n      clothParticles.position(j) -= correction;\n", "")],
     ["no-position-correction"], "no position correction"),
    ("cloth-impulse-not-split", ONLY22, C,
     [(IMPULSE_CLOTH, "        Eigen::Vector4f impulse = -(1 + coefRestitution) * normalVelocity;")],
     ["wrong-mass-split"], "impulse not divided by (invM_cloth + invM_sphere)"),
    ("cloth-normal-reversed", ONLY22, C,
     [("Eigen::Vector4f normal = _particles.position(i) - clothParticles.position(j);",
       "Eigen::Vector4f normal = clothParticles.position(j) - _particles.position(i);")],
     ["collision-normal-sign"], "contact normal from the sphere to the particle"),
    ("cloth-speed-cosines", ONLY22, C,
     [("Eigen::Vector4f relativeVelocity = _particles.velocity(i) - clothParticles.velocity(j);",
       "// each velocity split along the normal by its angle to it: |v| cos(angle)\n"
       "      Eigen::Vector4f vs = _particles.velocity(i), vp = clothParticles.velocity(j);\n"
       "      Eigen::Vector4f vsNormal = normal * (vs.norm() * (vs.dot(normal) / vs.norm()));\n"
       "      Eigen::Vector4f vpNormal = normal * (vp.norm() * (vp.dot(normal) / vp.norm()));\n"
       "      _particles.velocity(i) = (vs - vsNormal) + vsNormal;\n"
       "      clothParticles.velocity(j) = (vp - vpNormal) + vpNormal;\n"
       "      Eigen::Vector4f relativeVelocity = _particles.velocity(i) - clothParticles.velocity(j);")],
     ["division-by-speed"], "velocities split along the normal with a cosine over the speed: NaN for a body at rest"),
    ("cloth-touching-skipped", ONLY22, C, [("if (penetration < 0) continue;", "if (penetration <= 0) continue;")],
     ["touching-skipped"], "a particle exactly on the surface is not a contact"),
    ("cloth-full-correction", ONLY22, C,
     [("Eigen::Vector4f correction = (penetration * normal) * 0.15f;", "Eigen::Vector4f correction = penetration * normal;")],
     [], "position correction of the whole penetration instead of 0.15 of it"),
    # Spheres::collide()
    ("spheres-restitution-ignored", ONLY22, P,
     [("(-(1 + coefRestitution) * normalVelocity)", "(-normalVelocity)")],
     ["restitution-ignored"], "sphere-sphere impulse without (1 + e)"),
    ("spheres-restitution-changed", ONLY22, P,
     [("constexpr float coefRestitution = 0.8f;", "constexpr float coefRestitution = 1.0f;")],
     ["restitution-ignored"], "coefRestitution changed from 0.8f to 1.0f"),
    ("spheres-pair-twice", ONLY22, P,
     [("    for (int j = i + 1; j < sphereCount; ++j) {\n",
       "    for (int j = 0; j < sphereCount; ++j) {\n      if (i == j) continue;\n")],
     ["pair-processed-twice"], "every pair processed twice (j over all spheres)"),
    ("spheres-no-approach-check", ONLY22, P, [("      if (approach < 0) {\n", "      {\n")],
     ["no-approach-check"], "sphere-sphere impulse even when separating"),
    ("spheres-correction-one-body", ONLY22, P, [("      _particles.position(j) -= correction;\n", "")],
     ["correction-one-body"], "sphere-sphere correction moves sphere i only"),
    # ExplicitEuler::integrate
    ("explicit-first-body-only", BOTH, E,
     [("  for (const auto &p : particles) {\n", "  {\n    Particles* p = particles[0];\n")],
     ["only-first-body"], "only particles[0] (the cloth) integrated: spheres never move"),
    ("explicit-position-not-integrated", ONLY22, E, [("    p->position() += p->velocity() * deltaTime;\n", "")],
     ["position-not-integrated"], "x += v dt missing"),
    ("explicit-velocity-not-integrated", ONLY22, E, [("    p->velocity() += p->acceleration() * deltaTime;\n", "")],
     ["velocity-not-integrated"], "v += a dt missing"),
    ("explicit-position-uses-acceleration", ONLY22, E,
     [("p->position() += p->velocity() * deltaTime;",
       "p->position() += p->velocity() * deltaTime + 0.5f * p->acceleration() * deltaTime * deltaTime;")],
     ["position-uses-acceleration"], "x += v dt + a dt^2 / 2"),
    # ImplicitEuler::integrate
    ("implicit-pointer-backup", BOTH, I,
     [(BACKUP_COMMENT, ""), (BACKUP, "  auto backup = particles;\n"), ("backup[i].", "backup[i]->", 2)],
     ["backup-alias"], "auto backup = particles; copies the pointers, not the state"),
    ("implicit-no-reevaluation", ONLY22, I, [("  simulateOneStep();\n", "")],
     ["no-reevaluation"], "simulateOneStep() not called at the predicted state"),
    # MidpointEuler::integrate
    ("midpoint-ref-backup", ONLY22, M, [(BACKUP + "\n" + PREDICT_HALF + "  simulateOneStep();\n" + CORRECT, MIDPOINT_REF_BACKUP)],
     ["backup-alias"], "auto x0 = particles[0]->position(); is an Eigen::Ref view, not a copy"),
    ("midpoint-no-reevaluation", ONLY22, M, [("  simulateOneStep();\n", "")],
     ["no-reevaluation"], "midpoint without simulateOneStep() at the half step"),
    ("midpoint-full-step", ONLY22, M, [(" * deltaTime * 0.5f;", " * deltaTime;", 2)],
     ["midpoint-full-step"], "prediction with a full step (this is the implicit method)"),
    ("midpoint-deltatime-mutated", ONLY22, M,
     [(PREDICT_HALF, "  deltaTime = deltaTime / 2;\n" + PREDICT_FULL.replace("deltaTime;", "deltaTime;")),
      (CORRECT, CORRECT.replace(" * deltaTime;", " * deltaTime * 2;", 2))],
     ["deltatime-mutated"], "halves the global deltaTime for the half step and never restores it"),
    ("midpoint-integer-half", ONLY22, M, [(" * deltaTime * 0.5f;", " * deltaTime * (1 / 2);", 2)],
     ["integer-division-half"], "half step written * (1 / 2): integer zero"),
    # RungeKuttaFourth::integrate
    ("rk4-integer-sixth", BOTH, R,
     [(FINAL_X, "(1 / 6) * (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x[i])"),
      (FINAL_V, "(1 / 6) * (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v[i])")],
     ["integer-division-rk4"], "(1 / 6) * (...): integer zero, the state does not move"),
    ("rk4-equal-weights", ONLY22, R,
     [(FINAL_X, "(k1x[i] + k2x[i] + k3x[i] + k4x[i]) / 4.0f"), (FINAL_V, "(k1v[i] + k2v[i] + k3v[i] + k4v[i]) / 4.0f")],
     ["rk4-wrong-weights"], "stage weights (1, 1, 1, 1) / 4"),
    ("rk4-mixed-increments", ONLY22, R,
     [("particles[i]->position() = backup[i].position() + k2x[i] * 0.5f;",
       "particles[i]->position() = backup[i].position() + k2v[i] * 0.5f;")],
     ["rk4-mixed-increments"], "third stage position built from the velocity increment k2v"),
    ("rk4-stage-from-current", ONLY22, R,
     [("particles[i]->position() = backup[i].position() + k2x[i] * 0.5f;", "particles[i]->position() += k2x[i] * 0.5f;"),
      ("particles[i]->velocity() = backup[i].velocity() + k2v[i] * 0.5f;", "particles[i]->velocity() += k2v[i] * 0.5f;"),
      ("particles[i]->position() = backup[i].position() + k3x[i];", "particles[i]->position() += k3x[i];"),
      ("particles[i]->velocity() = backup[i].velocity() + k3v[i];", "particles[i]->velocity() += k3v[i];")],
     ["rk4-stage-not-from-backup"], "stages 3 and 4 start from the current state instead of x0"),
    ("rk4-first-body-only", ONLY22, R, [(LOOP_ALL, "for (size_t i = 0; i < 1; ++i) {", 5)],
     ["only-first-body"], "every RK4 loop stops after particles[0]"),
]


def write_mutants(full):
    for name, editions, stub, edits, diagnoses, description in MUTANTS:
        for edition in editions:
            ref = reference(edition)
            file = STUB_HEAD[stub][0]
            mutated = edit(ref[file], stub, edits)
            assert mutated != ref[file]
            mutated = f"// Grader corpus mutant `{name}` ({stub}): {description}.\n" + strip_header(mutated)
            directory = HERE / edition / name
            directory.mkdir(parents=True, exist_ok=True)
            extra = {}
            if full:
                for f in FILES:
                    (directory / f).write_text(mutated if f == file else ref[f])
            else:
                (directory / file).write_text(mutated)
                extra["base"] = f"{edition}/reference"
            write_expected(directory, edition, "mutant", description, [stub], diagnoses, **extra)


CHANGED_HEADER_HELPER = """\
void Cloth::addSpring(int start, int end, Spring::Type type) {
  _springs.emplace_back(start, end, (_particles.position(start) - _particles.position(end)).norm(), type);
}

"""


CHANGED_CLOTH_H = """\
#pragma once
#include <glad/gl.h>

#include <vector>

#include "buffer.h"
#include "shape.h"
#include "spring.h"
#include "utils.h"
#include "vertexarray.h"

class Cloth final : public Shape {
 public:
  MOVE_ONLY(Cloth)
  enum class DrawType { FULL, STRUCTURAL, SHEAR, BEND, PARTICLE };
  Cloth();

  std::vector<Spring>& springs() { return _springs; }
  void draw(DrawType type) const;
  void computeSpringForce();
  void computeNormal();
  void collide(Shape* shape) override;
  void collide(Spheres* sphere) override;

 private:
  void initializeVertex();
  void initializeSpring();
  // added by the student
  void addSpring(int start, int end, Spring::Type type);

  std::vector<Spring> _springs;
  VertexArray vao;
  ArrayBuffer positionBuffer;
  ArrayBuffer normalBuffer;
@TEXTURE  ElementArrayBuffer ebo, structuralSpring, shearSpring, bendSpring;
};
"""


def write_changed_header(edition):
    """cloth.cpp uses a helper the student declared in their own cloth.h: it does not compile
    against the course's headers, so both cloth stubs get a compile error; the rest is graded."""
    ref = reference(edition)
    cloth = ref["cloth.cpp"].replace("void Cloth::initializeSpring() {", CHANGED_HEADER_HELPER + "void Cloth::initializeSpring() {")
    cloth = edit(cloth, S, [(", structrualLength, Spring::Type::STRUCTURAL);", ", Spring::Type::STRUCTURAL);", 2),
                            ("_springs.emplace_back(", "addSpring(", 6),
                            (", shearLength, Spring::Type::SHEAR);", ", Spring::Type::SHEAR);", 2),
                            (", bendLength, Spring::Type::BEND);", ", Spring::Type::BEND);", 2)])
    directory = HERE / edition / "changed-header"
    (directory / "include").mkdir(parents=True, exist_ok=True)
    (directory / "src").mkdir(parents=True, exist_ok=True)
    (directory / "src" / "cloth.cpp").write_text(cloth)
    (directory / "src" / "sphere.cpp").write_text(ref["sphere.cpp"])
    (directory / "src" / "integrator.cpp").write_text(ref["integrator.cpp"])
    (directory / "include" / "cloth.h").write_text(
        CHANGED_CLOTH_H.replace("@TEXTURE", "  ArrayBuffer textureBuffer;\n" if edition == "2024" else ""))
    write_expected(directory, edition, "mutant",
                   "cloth.cpp defines Cloth::addSpring, declared only in the student's changed cloth.h: "
                   "compile error for cloth.cpp, the other two files still graded",
                   [S, F], ["compile-error"], compile_errors=["cloth.cpp"])


README_HEAD = """\
# Grader test corpus

Student-style submissions for `clothref grade`, per edition: `<edition>/<case>/` holds the hand-in
(the three course files, anywhere below it; `src/` is preferred) and `expected.json` (schema:
`tools/grader/expected.schema.json`): `kind` `correct` must score 100 %; a `mutant` must lose
points in exactly `stubs_losing_points` and no other stub, and its feedback must name each id in
`diagnoses` (ids from `tools/grader/diagnoses.json`; empty when the catalogue has no entry).

A mutant is one realistic mistake in one stub. Its directory holds only the changed file; `base`
names the submission (relative to this folder) that supplies the other two files, which the file
here replaces by name. `files_used` (hand-in shapes) says which files the grader must pick, and
`compile_errors` which files must fail to compile against the course's headers.

Everything here is written by `make_corpus.py` from the course-form reference in
`tools/grader/reference/<edition>/` (regenerate after changing it: `python3 make_corpus.py`; every
mutant edit must still match exactly, or the script stops). `check_corpus.py` compiles every
case's files against the stand-in headers with `g++ -std=c++20 -fsyntax-only`.

Some mistakes show only under a particular probe: `spring-hard-coded-25` only at another N;
`midpoint-deltatime-mutated` gives the right first step (it halves the global `deltaTime` and
scales back) and is caught by "deltaTime unchanged afterwards"; `cloth-touching-skipped` needs an
approaching particle at penetration exactly 0 with no other contact moving the sphere first;
`midpoint-ref-backup` assumes two bodies, as the course's main passes; `force-dangling-auto` is
undefined behaviour (it segfaults with g++ 12 at -O1 and -O2). `accepted-variants` and
`student-zip` give other trajectories and other float rounding than the reference (summation
order, scalar impulse), so they score 100 % only with tolerances on a sensible scale.

## Cases
"""


def write_readme():
    lines = [README_HEAD]
    for edition in ("2022", "2024"):
        lines.append(f"\n### {edition}\n\n| case | kind | stubs losing points | diagnoses | what |\n|---|---|---|---|---|\n")
        for expected_path in sorted((HERE / edition).glob("*/expected.json")):
            expected = json.loads(expected_path.read_text())
            losing = ", ".join(f"`{s}`" for s in expected["stubs_losing_points"]) or "none"
            diagnoses = ", ".join(f"`{d}`" for d in expected["diagnoses"]) or "-"
            lines.append(f"| `{expected_path.parent.name}` | {expected['kind']} | {losing} | "
                         f"{diagnoses} | {expected['description']} |\n")
    (HERE / "README.md").write_text("".join(lines))


def main():
    full = "--full" in sys.argv[1:]
    for edition in ("2022", "2024"):
        # the corpus is regenerated whole: nothing stale survives
        shutil.rmtree(HERE / edition, ignore_errors=True)
        write_reference_submission(edition)
        write_zip_submission(edition)
        write_variants_submission(edition)
        write_changed_header(edition)
    write_mutants(full)
    write_readme()


if __name__ == "__main__":
    main()
