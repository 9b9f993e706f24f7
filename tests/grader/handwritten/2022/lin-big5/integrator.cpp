#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration
  //   1. Integrate velocity.
  //   2. Integrate acceleration.
  //   3. You should not compute position using acceleration. Since some part only update velocity. (e.g. impulse)
  // Note:
  //   1. You don't need the simulation function in explicit euler.
  //   2. You should do this first because it is very simple. Then you can check your collision is correct or not.
  //   3. This can be done in 2 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
	for (const auto &p : particles) {
		p->position() += p->velocity() * deltaTime;
		p->velocity() += p->acceleration() * deltaTime;
	}
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
	// 備份
	std::vector<Particles> backup;
	for (auto p : particles) backup.push_back(*p);
	// 用 explicit euler 先算出下一步
	for (auto p : particles) {
		p->position() += p->velocity() * deltaTime;
		p->velocity() += p->acceleration() * deltaTime;
	}
	simulateOneStep();
	// 用下一步的速度和加速度更新
	for (int i = 0; i < (int)particles.size(); i++) {
		particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
		particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
	}
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
	std::vector<Particles> backup;
	for (auto p : particles) backup.push_back(*p);
	float half = deltaTime * 0.5f;
	// 走到中點 (先速度再位置)
	for (auto p : particles) {
		p->velocity() += p->acceleration() * half;
		p->position() += p->velocity() * half;
	}
	simulateOneStep();
	for (int i = 0; i < (int)particles.size(); i++) {
		particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
		particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
	}
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Compute k1, k2, k3, k4
  //   3. Compute refined Xn+1 using (1.) (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
	std::vector<Particles> backup;
	for (auto p : particles) backup.push_back(*p);
	int n = (int)particles.size();
	std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
	for (int k = 0; k < 4; k++) {
		if (k > 0) simulateOneStep();
		for (int i = 0; i < n; i++) {
			kx[k].push_back(particles[i]->velocity() * deltaTime);
			kv[k].push_back(particles[i]->acceleration() * deltaTime);
		}
		if (k == 3) break;
		float scale = (k == 2) ? 1.0f : 0.5f;  // k1,k2 走半步, k3 走一步
		for (int i = 0; i < n; i++) {
			particles[i]->position() = backup[i].position() + kx[k][i] * scale;
			particles[i]->velocity() = backup[i].velocity() + kv[k][i] * scale;
		}
	}
	// 加權平均
	for (int i = 0; i < n; i++) {
		particles[i]->position() = backup[i].position() + (1 / 6) * (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]);
		particles[i]->velocity() = backup[i].velocity() + (1 / 6) * (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]);
	}
}
