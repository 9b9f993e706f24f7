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
		p->position() += deltaTime * p->velocity();
		p->velocity() += deltaTime * p->acceleration();
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
	// 1. 備份
	std::vector<Particles> backup;
	for (const auto &p : particles) backup.push_back(*p);
	// 算 X(n+1) 的力
	simulateOneStep();
	// 2. explicit euler
	for (const auto &p : particles) {
		p->position() += p->velocity() * deltaTime;
		p->velocity() += p->acceleration() * deltaTime;
	}
	// 3. X(n+1) = X(n) + h * f(X(n+1))
	for (size_t i = 0; i < particles.size(); i++) {
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
	for (const auto &p : particles) backup.push_back(*p);
	for (const auto &p : particles) {
		p->position() += p->velocity() * deltaTime * 0.5f;
		p->velocity() += p->acceleration() * deltaTime * 0.5f;
	}
	simulateOneStep();
	for (size_t i = 0; i < particles.size(); i++) {
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
	for (const auto &p : particles) backup.push_back(*p);
	const size_t n = particles.size();
	std::vector<Eigen::Matrix4Xf> kx[4], kv[4];

	// 取得目前狀態的 k
	auto takeK = [&](int s) {
		for (size_t i = 0; i < n; i++) {
			kx[s].push_back(particles[i]->velocity() * deltaTime);
			kv[s].push_back(particles[i]->acceleration() * deltaTime);
		}
	};
	// 設定成 x0 + k * c
	auto setState = [&](int s, float c) {
		for (size_t i = 0; i < n; i++) {
			particles[i]->position() = backup[i].position() + kx[s][i] * c;
			particles[i]->velocity() = backup[i].velocity() + kv[s][i] * c;
		}
	};

	takeK(0);
	setState(0, 0.5f);
	simulateOneStep();
	takeK(1);
	setState(1, 0.5f);
	simulateOneStep();
	takeK(2);
	setState(2, 1.0f);
	simulateOneStep();
	takeK(3);

	for (size_t i = 0; i < n; i++) {
		particles[i]->position() = backup[i].position() + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
		particles[i]->velocity() = backup[i].velocity() + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
	}
}
