"""Masses, springs and energies of a trace's scene (the library's cloth.h / spheres.h rules).

masses(scene)             {"cloth": (N,), "spheres": (M,)} kg; 0 = fixed
springs(scene, x0)        (start, end, rest_length) arrays; a grid cloth gets the course's six
                          passes with rest lengths measured from the initial positions x0 (N, 3)
energies(scene, bodies, x0)  kinetic, spring and gravitational energy (J) of one state
The spring potential is 1/2 k_s (L - L0)^2 per spring (dampers store none); the gravitational one
is -m g . x, so a particle at y = 0 has none. Spheres feel gravity only with external_force.
"""
import numpy as np


def masses(scene):
    out = {}
    cloth = scene.get("cloth")
    if cloth is not None:
        if cloth.get("grid"):
            n = int(cloth["grid"]["particles_per_edge"])
            m = np.full(n * n, float(cloth["grid"]["particle_mass"]))
        else:
            m = np.array([float(p["mass"]) for p in cloth["particles"]])
        m[list(cloth.get("fixed", []))] = 0.0
        out["cloth"] = m
    spheres = scene.get("spheres")
    if spheres is not None:
        density = float(spheres["density"])
        out["spheres"] = np.array([
            float(s["mass"]) if s.get("mass") is not None
            else density * float(s["radius"]) * float(s["radius"]) * float(s["radius"])
            for s in spheres["items"]])
    return out


def springs(scene, x0):
    cloth = scene.get("cloth")
    if cloth is None:
        return np.zeros(0, int), np.zeros(0, int), np.zeros(0)
    if not cloth.get("grid"):
        s = cloth.get("springs", [])
        return (np.array([min(a["start"], a["end"]) for a in s], dtype=int),
                np.array([max(a["start"], a["end"]) for a in s], dtype=int),
                np.array([float(a["rest_length"]) for a in s]))
    n = int(cloth["grid"]["particles_per_edge"])
    start, end, rest = [], [], []

    def add(pairs, length):
        for a, b in pairs:
            start.append(a)
            end.append(b)
            rest.append(length)

    structural = np.linalg.norm(x0[0] - x0[1])
    add([(i * n + j, i * n + j + 1) for i in range(n) for j in range(n - 1)], structural)
    add([(i * n + j, i * n + j + n) for i in range(n - 1) for j in range(n)], structural)
    shear = np.linalg.norm(x0[0] - x0[n + 1])
    add([(i * n + j, i * n + j + n + 1) for i in range(n - 1) for j in range(n - 1)], shear)
    add([(i * n + j, i * n + j + n - 1) for i in range(n - 1) for j in range(1, n)], shear)
    if n >= 3:
        bend = np.linalg.norm(x0[0] - x0[2])
        add([(i * n + j, i * n + j + 2) for i in range(n) for j in range(n - 2)], bend)
        add([(i * n + j, i * n + j + 2 * n) for i in range(n - 2) for j in range(n)], bend)
    return np.array(start, dtype=int), np.array(end, dtype=int), np.array(rest)


class EnergyModel:
    """Energies of states of one scene; x0 is the cloth's initial positions (N, 3)."""

    def __init__(self, scene, x0):
        self.scene = scene
        self.masses = masses(scene)
        self.gravity = np.array(scene["gravity"], dtype=float)
        self.start, self.end, self.rest = springs(scene, x0 if x0 is not None else np.zeros((0, 3)))
        self.spring_coef = float(scene["cloth"]["spring_coef"]) if scene.get("cloth") else 0.0

    def energies(self, bodies):
        """{"kinetic", "spring", "gravitational", "total"} in joules for one state."""
        kinetic = gravitational = spring = 0.0
        for name, m in self.masses.items():
            if name not in bodies:
                continue
            v = bodies[name]["velocity"]
            x = bodies[name]["position"]
            kinetic += 0.5 * float(np.sum(m * np.sum(v * v, axis=1)))
            if name == "cloth" or self.scene["spheres"].get("external_force", False):
                gravitational -= float(np.sum(m * (x @ self.gravity)))
        if "cloth" in bodies and len(self.start):
            x = bodies["cloth"]["position"]
            length = np.linalg.norm(x[self.start] - x[self.end], axis=1)
            spring = 0.5 * self.spring_coef * float(np.sum((length - self.rest) ** 2))
        return {"kinetic": kinetic, "spring": spring, "gravitational": gravitational,
                "total": kinetic + spring + gravitational}
