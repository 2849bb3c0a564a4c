// fix ID group nve/sphere: velocity Verlet for translation and rotation of
// spheres (moment of inertia 2/5 m r^2). Rotation is skipped when no grain
// can spin (frozen-rotation scenes pay nothing for it).
#include "core/simulation.h"
#include "core/style_registry.h"

namespace sable {

class FixNveSphere : public Fix {
 public:
  FixNveSphere(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = INITIAL_INTEGRATE | FINAL_INTEGRATE;
    for (std::size_t i = 4; i < a.size(); ++i)
      if (a[i] != "update" && a[i] != "dipole" && a[i] != "disc") a.fail(i, "nothing (or update dipole/disc)");
  }
  void initial_integrate() override {
    kick();
    Atoms& at = sim.atoms;
    const double dt = sim.dt;
    double* x = at.x.data();
    const double* v = at.v.data();
#pragma omp parallel for schedule(static) if (at.n > 20000)
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      for (int k = 0; k < 3; ++k) x[3 * i + k] += dt * v[3 * i + k];
    }
  }
  void final_integrate() override { kick(); }

 private:
  // Half-step velocity and spin update from force and torque.
  void kick() {
    Atoms& at = sim.atoms;
    const double h = 0.5 * sim.dt;
    double* v = at.v.data();
    double* w = at.omega.data();
    const double* f = at.f.data();
    const double* t = at.torque.data();
#pragma omp parallel for schedule(static) if (at.n > 20000)
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      const double m = at.rmass[i], r = at.radius[i];
      const double hm = h / m, hi = h / (0.4 * m * r * r);
      for (int k = 0; k < 3; ++k) {
        v[3 * i + k] += hm * f[3 * i + k];
        w[3 * i + k] += hi * t[3 * i + k];
      }
    }
  }
};

SABLE_FIX("nve/sphere", FixNveSphere);

}  // namespace sable
