// fix ID group freeze: zero the force and torque on the group after all forces
// are known (LIGGGHTS: post_force; velocities are left alone, so a frozen grain
// with a velocity keeps drifting at that velocity). f_ID[1..3] is the total force
// on the group before it was zeroed. One freeze fix at most (pair styles look it up).
#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "core/simulation.h"
#include "core/style_registry.h"
#include "core/threads.h"

namespace sable {

class FixFreeze : public Fix {
 public:
  FixFreeze(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = POST_FORCE;
    vector_size = 3;
    if (a.size() > 4) a.fail(4, "nothing after 'freeze'");
  }
  void init() override {
    bool after = false;
    for (auto& f : sim.fixes) {
      if (f.get() == this) {
        after = true;
        continue;
      }
      if (f->style == "freeze")
        args.fail_line("more than one fix freeze (LIGGGHTS allows one; also fix '" + f->id + "')");
      if (after && (f->hooks & POST_FORCE) && f->acceleration() > 0)
        sim.warn("fix freeze " + id + ": fix " + f->style + " '" + f->id +
                 "' is defined after it and adds force to frozen grains after they are frozen (as in LIGGGHTS); "
                 "define fix freeze after it to keep them still");
    }
    const Atoms& at = sim.atoms;
    long moving = 0;
    for (std::size_t i = 0; i < at.n; ++i)
      if (at.mask[i] & groupbit)
        for (int k = 0; k < 3; ++k)
          if (at.v[3 * i + k] != 0 || at.omega[3 * i + k] != 0) {
            ++moving;
            break;
          }
    if (moving)
      sim.warn("fix freeze " + id + ": " + std::to_string(moving) +
               " frozen grains have a velocity or spin and keep it (as in LIGGGHTS); use 'velocity " +
               sim.groups.name(group) + " set 0 0 0' to hold them still");
  }
  // Ranged (pipelined step): each thread zeroes its own grains and sums their
  // forces in fixed blocks of kBlock atoms. A block cut by a range bound is
  // continued in finish() with the later ranges' values, in atom order: the
  // additions of one serial pass over the blocks, so f_ID has the same bits
  // for any thread count.
  bool post_force_ranged() const override { return true; }
  void post_force_prepare() override {
    block_.assign((sim.atoms.n + kBlock - 1) / kBlock, {0.0, 0.0, 0.0});
    parts_.resize(atom_pass_threads());
    for (Part& p : parts_) p.clear();
  }
  void post_force_range(int t, std::size_t lo, std::size_t hi) override {
    Atoms& at = sim.atoms;
    Part& head = parts_[t];
    for (std::size_t a = lo; a < hi;) {
      const std::size_t b = a / kBlock, end = std::min(hi, (b + 1) * kBlock);
      const bool cut = a == lo && lo % kBlock != 0;  // the block began in an earlier range
      if (cut) head.block = b;
      for (std::size_t i = a; i < end; ++i) {
        if (!(at.mask[i] & groupbit)) continue;
        for (int k = 0; k < 3; ++k) {
          if (cut)
            head.f.push_back(at.f[3 * i + k]);
          else
            block_[b][k] += at.f[3 * i + k];
          at.f[3 * i + k] = 0;
          at.torque[3 * i + k] = 0;
        }
      }
      a = end;
    }
  }
  void post_force_finish() override {
    for (const Part& p : parts_)  // ranges in atom order
      for (std::size_t q = 0; q < p.f.size(); ++q) block_[p.block][q % 3] += p.f[q];
    for (double& s : f0_) s = 0.0;
    for (const auto& s : block_)
      for (int k = 0; k < 3; ++k) f0_[k] += s[k];
  }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? f0_[i - 1] : 0.0; }

 private:
  static constexpr std::size_t kBlock = 1024;
  struct alignas(64) Part {  // a range's grains in a block that began before it
    std::size_t block = 0;
    std::vector<double> f;   // their forces, 3 per grain of the group, in atom order
    void clear() { f.clear(); }
  };
  std::vector<std::array<double, 3>> block_;  // per block: the forces summed so far
  std::vector<Part> parts_;                   // per range
  double f0_[3] = {0, 0, 0};
};

SABLE_FIX("freeze", FixFreeze);

}  // namespace sable
