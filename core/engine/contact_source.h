#pragma once
// Where contacts come from, as their consumers see them: the pair style's grain
// pairs, a primitive wall, a mesh wall. Computes and dumps that need contacts ask
// contact_sources() and never name a concrete pair or fix.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/engine/contact_loop.h"
#include "core/engine/neighbor.h"

namespace sable {

class Simulation;

class ContactSource {
 public:
  enum class Kind { Pairs, Wall, Mesh };
  virtual ~ContactSource() = default;

  virtual Kind contact_kind() const = 0;
  virtual std::string law_name() const = 0;  // the contact law, for messages
  virtual const std::vector<HistorySlot>& history_slots() const = 0;
  // Every contact of grains of `groupbit` at the current state; forces and history
  // are evaluated, not advanced. A wall's record r names its contact by r.shift:
  // wall_point(r.shift), wall_velocity(r.shift), element(r.shift).
  virtual void records(std::uint32_t groupbit, ContactRecords& out) = 0;
  virtual const double* wall_point(int /*k*/) const { return nullptr; }
  virtual const double* wall_velocity(int /*k*/) const { return nullptr; }
  virtual int element(int /*k*/) const { return 0; }  // a mesh's triangle; 0 elsewhere

  // The contacts of the last force pass, as that pass saw them: fn(atom, wall point,
  // force on the grain). False (fn not called) where the source keeps none, or the
  // atoms were sorted or deleted since: ask records() then.
  using PassFn = std::function<void(int, const double*, const double*)>;
  virtual bool last_pass(const PassFn& /*fn*/) const { return false; }
  // A flat wall's normal axis (0, 1, 2); -1 for any other source.
  virtual int plane_axis() const { return -1; }
  // Grain ids changed (delete_atoms ... compress yes): grain old_ids[k] is now
  // new_ids[k], old_ids ascending, new_ids in the same order; ids not listed are
  // gone. History kept by grain id follows.
  virtual void ids_renumbered(const std::vector<long>& /*old_ids*/, const std::vector<long>& /*new_ids*/) {}
  // Several ranks (Comm::exchange): a wall's history by grain id (a mesh wall: one
  // store per mesh), brought up to date, to move with the grains; none for a source
  // that keeps none this way (the pair's rows travel from Neighbor's ContactStore).
  // history_moved(): rows were cut or received.
  virtual std::vector<HistoryStore*> histories_by_grain() { return {}; }
  virtual void history_moved() {}
};

// The run's contact sources: the pair style's, if it has contacts, then every
// fix's in the order the deck defined them.
std::vector<ContactSource*> contact_sources(Simulation& sim);

// The pair style's grain pairs (nullptr: no pair style with contacts).
ContactSource* pair_contacts(Simulation& sim);

// The source of fix `id` (nullptr: no such fix, or it is no contact source).
ContactSource* contact_source_of_fix(Simulation& sim, const std::string& id);

}  // namespace sable
