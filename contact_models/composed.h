#pragma once
// Laws composed at run time. The build compiles the fast kernels
// (GranKernel, kernel.h) only for the combinations listed in
// contact_models/compiled_laws.txt; any other combination of registered
// sub-models runs here: each sub-model sits behind one virtual call per chunk
// of contacts (a normal model together with its damping model, which may read
// it), and the steps between them are kernel.h's (damped_normal_force,
// add_cohesion, contact_parts), so a composed law gives the compiled law's
// bits. Slower: no vector loop across the axes, one pass per axis.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "contact_models/kernel.h"

namespace sable {

// One sub-model as a composed law sees it: keywords, coefficients, history.
class LawPart {
 public:
  virtual ~LawPart() = default;
  virtual void settings(ModelSettings& s) = 0;
  virtual void connect(PropertyRequest& p) = 0;
  virtual int history() const = 0;  // doubles per contact
  virtual void history_slots(std::vector<HistorySlot>& s) const = 0;
};

// Each part evaluates contacts c[0..n); contact m's history starts at h + m * hs.
class NormalPart : public LawPart {
 public:
  virtual void forces(const Contact* c, int n, double* h, int hs, const StepContext& ctx, NormalForce* nf) const = 0;
  virtual double contact_time(const ContactTimeInput& in) const = 0;
};
class TangentialPart : public LawPart {
 public:
  virtual void forces(const Contact* c, const NormalForce* nf, int n, double* h, int hs, const StepContext& ctx,
                      Vec3* ft) const = 0;
};
class RollingPart : public LawPart {
 public:
  virtual void torques(const Contact* c, const NormalForce* nf, int n, double* h, int hs, const StepContext& ctx,
                       Vec3* mr) const = 0;
};
class CohesionPart : public LawPart {
 public:
  virtual bool active() const = 0;  // false: the law skips the axis (CohesionOff::kActive)
  // The pull into nf[m].Fn or into fcoh[m] (add_cohesion).
  virtual void forces(const Contact* c, NormalForce* nf, int n, double* h, int hs, const StepContext& ctx,
                      double* fcoh) const = 0;
};

// The part of sub-model M (a struct of contact_models/<axis>/).
template <class M, class Base>
class PartOf : public Base {
 public:
  void settings(ModelSettings& s) override { m_.settings(s); }
  void connect(PropertyRequest& p) override { m_.connect(p); }
  int history() const override { return M::kHistory; }
  void history_slots(std::vector<HistorySlot>& s) const override { M::history_slots(s); }

 protected:
  M m_;
};

// A normal model with one damping model: compiled together, since the damping
// model reads what the normal one exports (damping liggghts: its LIGGGHTS form).
template <class N, class D>
class NormalPartOf final : public PartOf<N, NormalPart> {
 public:
  void settings(ModelSettings& s) override {
    this->m_.settings(s);
    damping_.settings(s);
  }
  void connect(PropertyRequest& p) override {  // as GranKernel::connect
    this->m_.connect(p);
    p.set_who(std::string("damping ") + D::kName);
    damping_.connect(p, this->m_);
  }
  int history() const override { return N::kHistory + D::kHistory; }
  void history_slots(std::vector<HistorySlot>& s) const override {
    N::history_slots(s);
    D::history_slots(s);
  }
  void forces(const Contact* c, int n, double* h, int hs, const StepContext& ctx, NormalForce* nf) const override {
    for (int m = 0; m < n; ++m) nf[m] = damped_normal_force(this->m_, damping_, c[m], h + m * hs, ctx);
  }
  double contact_time(const ContactTimeInput& in) const override { return law_contact_time(this->m_, damping_, in); }

 private:
  D damping_;
};

template <class T>
class TangentialPartOf final : public PartOf<T, TangentialPart> {
 public:
  void forces(const Contact* c, const NormalForce* nf, int n, double* h, int hs, const StepContext& ctx,
              Vec3* ft) const override {
    for (int m = 0; m < n; ++m) ft[m] = this->m_.force(c[m], nf[m], h + m * hs, ctx);
  }
};

template <class R>
class RollingPartOf final : public PartOf<R, RollingPart> {
 public:
  void torques(const Contact* c, const NormalForce* nf, int n, double* h, int hs, const StepContext& ctx,
               Vec3* mr) const override {
    for (int m = 0; m < n; ++m) mr[m] = this->m_.torque(c[m], nf[m], h + m * hs, ctx);
  }
};

template <class C>
class CohesionPartOf final : public PartOf<C, CohesionPart> {
 public:
  bool active() const override { return C::kActive; }
  void forces(const Contact* c, NormalForce* nf, int n, double* h, int hs, const StepContext& ctx,
              double* fcoh) const override {
    for (int m = 0; m < n; ++m)
      fcoh[m] = add_cohesion(nf[m], this->m_.force(c[m], nf[m], h + m * hs, ctx), this->m_.reduces_tangential());
  }
};

// The parts of one law and its names (normal, damping, tangential, rolling, cohesion).
struct ComposedParts {
  std::array<std::string, 5> names;
  std::unique_ptr<NormalPart> normal;
  std::unique_ptr<TangentialPart> tangential;
  std::unique_ptr<RollingPart> rolling;
  std::unique_ptr<CohesionPart> cohesion;
  int history() const { return normal->history() + tangential->history() + rolling->history() + cohesion->history(); }
};

// The law of these parts (history() <= kMaxLoopHistory).
std::unique_ptr<ContactKernel> make_composed_kernel(ComposedParts parts);

}  // namespace sable
