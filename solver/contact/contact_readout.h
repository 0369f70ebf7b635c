// What the outputs read of the contacts (contacts.csv, the Python module's contacts()): one row
// per contact of the step's set — where its vertex is, its state and joint set, the springs'
// closure, shear, forces and tangent stiffnesses, its tributary length, the water pressure in
// its joint and its Barton–Bandis state. Forces in N (per m of thickness), stiffnesses N/m.
#pragma once

#include <vector>

#include "solver/contact/contact_set.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// One contact at one output step (contacts.csv).
struct ContactSample {
  double x, y;             ///< m, the contact vertex
  int state;               ///< 0 open, 1 locked, 2 sliding
  int law;                 ///< joint set index (or the default interface's, last)
  double closure;          ///< m, −gap (> 0: the faces overlap by this much), the normal spring's:
                           ///< net of a Barton–Bandis joint's dilation (faces apart by dilation − closure)
  double shear;            ///< m, elastic shear of the shear spring
  double normal_force;     ///< N, compression
  double shear_force;      ///< N
  double kn, ks;           ///< N/m, tangent stiffnesses (0 where the spring is off)
  double length;           ///< m, tributary joint length
  int vertex;              ///< loop vertex P of the contact (Mesh::loop_xy index)
  int edge;                ///< first loop vertex of the edge P faces (edge → next vertex)
  double pressure = 0;     ///< Pa, water pressure in the joint at the contact (joint_water.h)
  double jrc_mob = 0;      ///< –, mobilised JRC (Barton–Bandis shear; 0 for the other laws)
  double dilation = 0;     ///< m, the joint's opening from shearing (Barton–Bandis; else 0)
};

/// The rows of `contacts` in state s of a run of `model`: the closed contacts (all of them with
/// `open_too`).
std::vector<ContactSample> contact_samples(const ContactSet& contacts, const Model& model, const RunState& s,
                                           bool open_too = false);

}  // namespace nmm::solve
