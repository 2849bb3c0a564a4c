// fix particletemplate/multisphere; see fixes/fix_particletemplate_multisphere.h.
#include "fixes/fix_particletemplate_multisphere.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/rigid_body_set.h"

namespace sable {

namespace {

// A relative file name is looked up from the working directory (LIGGGHTS), then from the deck's folder.
std::string find_beside(const std::string& name, const Args& a) {
  namespace fs = std::filesystem;
  if (fs::path(name).is_absolute() || fs::exists(name)) return name;
  const fs::path beside = fs::path(a.where().file).parent_path() / name;
  return fs::exists(beside) ? beside.string() : name;
}

std::array<bool, 3> on_off3(const Args& a, std::size_t i) {
  return {a.yes_no(i, "on or off"), a.yes_no(i + 1, "on or off"), a.yes_no(i + 2, "on or off")};
}

}  // namespace

bool MultisphereSpec::keyword(const Args& a, std::size_t& i) {
  const std::string& k = a[i];
  if (k == "nspheres") {
    nspheres = a.integer(i + 1, "the number of spheres");
    if (nspheres < 2) a.fail(i + 1, "nspheres >= 2 (LIGGGHTS: a clump has two or more spheres)");
    i += 2;
  } else if (k == "ntry") {
    ntry = a.integer(i + 1, "the number of Monte-Carlo points");
    if (ntry < 1000) a.fail(i + 1, "ntry >= 1000 (LIGGGHTS: 'ntry is too low')");
    // Two Monte-Carlo passes of ntry points each: 1e8 already takes seconds.
    if (ntry > 100000000) a.fail(i + 1, "ntry <= 100000000 (the Monte-Carlo passes would run for hours; LIGGGHTS' examples use 1e6)");
    i += 2;
  } else if (k == "spheres") {
    if (nspheres < 2) a.fail(i, "'nspheres N' before 'spheres'");
    if (a.word(i + 1, "'file F scale S' or the spheres as x y z r ...") == "file") {
      a.word(i + 2, "a sphere file name");
      if (a.word(i + 3, "'scale S' (LIGGGHTS requires a scale factor after the file)") != "scale")
        a.fail(i + 3, "'scale S' (LIGGGHTS requires a scale factor after the file)");
      const double s = a.num(i + 4, "the scale factor");
      if (!(s > 0)) a.fail(i + 4, "a scale factor > 0");
      read_file(a, i + 2, s);
      i += 5;
    } else {
      x.clear(), r.clear();
      for (long j = 0; j < nspheres; ++j) {
        const std::size_t at = i + 1 + 4 * j;
        const std::string what = " of sphere " + std::to_string(j + 1) + " of " + std::to_string(nspheres);
        x.push_back({a.num(at, "x" + what), a.num(at + 1, "y" + what), a.num(at + 2, "z" + what)});
        r.push_back(a.num(at + 3, "the radius" + what));
        if (!(r.back() > 0)) a.fail(at + 3, "a radius > 0");
      }
      i += 1 + 4 * nspheres;
    }
  } else if (k == "type") {
    const long t = a.integer(i + 1, "the multisphere type (1, 2, ...)");
    if (t < 1) a.fail(i + 1, "a multisphere type >= 1");
    ms_type = static_cast<int>(t);
    i += 2;
  } else if (k == "mass") {
    mass = a.num(i + 1, "the clump's mass");
    if (!(mass > 0)) a.fail(i + 1, "a mass > 0");
    i += 2;
  } else if (k == "inertia_tensor") {
    const char* names[6] = {"Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz"};
    const int slot[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    for (int c = 0; c < 6; ++c) {
      const double v = a.num(i + 1 + c, names[c]);
      tensor[3 * slot[c][0] + slot[c][1]] = tensor[3 * slot[c][1] + slot[c][0]] = v;
    }
    tensor_given = true;
    i += 7;
  } else if (k == "use_volume" || k == "use_density") {
    use_density = k == "use_density";
    i += 1;
  } else if (k == "fflag" || k == "tflag") {
    (k == "fflag" ? fflag : tflag) = on_off3(a, i + 1);
    i += 4;
  } else {
    return false;
  }
  return true;
}

// Lines "x y z r" ('#' starts a comment), exactly nspheres of them.
void MultisphereSpec::read_file(const Args& a, std::size_t at, double scale) {
  const std::string path = find_beside(a[at], a);
  std::ifstream in(path);
  if (!in) a.fail(at, "a readable sphere file (x y z r per line): cannot open '" + path + "'");
  x.clear(), r.clear();
  std::string line;
  long lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (const auto h = line.find('#'); h != std::string::npos) line.erase(h);
    std::istringstream ls(line);
    double v[4];
    int got = 0;
    while (got < 4 && ls >> v[got]) ++got;
    if (got == 0 && ls.eof()) continue;
    if (got != 4)
      a.fail(at, "a sphere file of lines 'x y z r': line " + std::to_string(lineno) + " of '" + path + "' is not");
    if (!(v[3] > 0)) a.fail(at, "radii > 0: line " + std::to_string(lineno) + " of '" + path + "'");
    x.push_back({v[0] * scale, v[1] * scale, v[2] * scale});
    r.push_back(v[3] * scale);
  }
  if (static_cast<long>(x.size()) != nspheres)
    a.fail(at, "a file with nspheres = " + std::to_string(nspheres) + " spheres: '" + path + "' has " +
                   std::to_string(x.size()));
}

FixParticletemplateMultisphere::FixParticletemplateMultisphere(Simulation& s, const Args& a)
    : MultisphereSpec(),
      FixParticletemplateSphere(s, a, [this](const Args& aa, std::size_t& i) { return keyword(aa, i); }) {
  finish(a);
}

void FixParticletemplateMultisphere::finish(const Args& a) {
  const std::size_t end = a.size();
  if (nspheres < 2) a.fail(end, "'nspheres N' (LIGGGHTS: expecting argument 'nspheres')");
  if (ntry < 1) a.fail(end, "'ntry M' (LIGGGHTS: need 'ntry' to be defined)");
  if (x.empty()) a.fail(end, "'spheres file F scale S' or 'spheres x1 y1 z1 r1 ...'");
  if (ms_type < 1) a.fail(end, "'type MT' (LIGGGHTS: have to provide a type >= 1)");
  if ((mass > 0) != tensor_given) a.fail(end, "both 'mass' and 'inertia_tensor' or neither (LIGGGHTS)");
  if (mass > 0 && use_density < 0) a.fail(end, "'use_volume' or 'use_density' with 'mass' and 'inertia_tensor'");
  if (density.style != Pdf::Constant) a.fail(end, "'density constant RHO' (LIGGGHTS: constant density only)");
  if (sim.domain.dimension != 3) a.fail(0, "dimension 3 (LIGGGHTS' multisphere templates are 3D only)");
  if (ntry < 100000) sim.warn("fix particletemplate/multisphere " + id + ": ntry is very low");

  double rho = density.a;
  if (mass < 0) {  // all from the Monte Carlo
    monte_carlo(true, true);
    shape_.mass = shape_.volume * rho;
  } else if (use_density == 0) {  // volume and centre from the Monte Carlo, the mass given
    monte_carlo(true, false);
    shape_.mass = mass;
    rho = mass / shape_.volume;
  } else {  // nothing from the Monte Carlo: the centre of mass is the spheres' origin
    shape_.mass = mass;
    shape_.volume = mass / rho;
  }
  shape_.density = rho;
  rigid::Body b;
  Eigen::Matrix3d I;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) I(p, q) = tensor[3 * p + q];
  rigid::principal_axes(b, I);
  shape_.moments = b.moments;
  shape_.q = b.q;
  shape_.radius = r;
  shape_.displace.clear();
  shape_.r_bound = 0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const rigid::V3 d{x[j][0] - xcm_[0], x[j][1] - xcm_[1], x[j][2] - xcm_[2]};
    shape_.displace.push_back({rigid::dot(d, b.ex), rigid::dot(d, b.ey), rigid::dot(d, b.ez)});
    shape_.r_bound = std::max(shape_.r_bound, std::sqrt(rigid::dot(d, d)) + r[j]);
  }
  shape_.fflag = fflag, shape_.tflag = tflag, shape_.ms_type = ms_type;
  radius.style = Pdf::Constant;
  radius.a = shape_.r_bound;  // the distribution's largest grain, the insertion overlap cut
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "Finished calculating properties of template %s\n   mass = %e, radius of bounding sphere = %e, "
                "volume = %e\n   center of mass (input frame) = %e, %e, %e\n   Principal moments of inertia: %e, %e, %e",
                id.c_str(), shape_.mass, shape_.r_bound, shape_.volume, xcm_[0], xcm_[1], xcm_[2], b.moments[0],
                b.moments[1], b.moments[2]);
  sim.print(buf);
}

// LIGGGHTS' estimator: uniform points in the spheres' bounding box, each inside
// any sphere counted once; the centre first (volume, centre of mass), then, on
// new points, the inertia tensor about that centre.
void FixParticletemplateMultisphere::monte_carlo(bool centre, bool inertia) {
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = 1e300, hi[k] = -1e300;
  for (std::size_t j = 0; j < x.size(); ++j)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[j][k] - r[j]), hi[k] = std::max(hi[k], x[j][k] + r[j]);
  const double box = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  auto draw = [&](double* p) {
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * rng_.uniform();
  };
  auto inside = [&](const double* p, const std::array<double, 3>& shift) {
    for (std::size_t j = 0; j < x.size(); ++j) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(p[k] - (x[j][k] - shift[k]), 2);
      if (d2 < r[j] * r[j]) return true;
    }
    return false;
  };
  if (centre) {
    long hits = 0;
    double sum[3] = {0, 0, 0};
    for (long t = 0; t < ntry; ++t) {
      double p[3];
      draw(p);
      if (!inside(p, {0, 0, 0})) continue;
      ++hits;
      for (int k = 0; k < 3; ++k) sum[k] += p[k];
    }
    for (int k = 0; k < 3; ++k) xcm_[k] = hits ? sum[k] / hits : 0.0;
    shape_.volume = static_cast<double>(hits) / ntry * box;
  }
  if (!inertia) return;
  for (int k = 0; k < 3; ++k) lo[k] -= xcm_[k], hi[k] -= xcm_[k];  // the box about the centre
  tensor.fill(0);
  for (long t = 0; t < ntry; ++t) {
    double p[3];
    draw(p);
    if (!inside(p, xcm_)) continue;
    const double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) tensor[3 * a + b] += (a == b ? r2 : 0.0) - p[a] * p[b];
  }
  const double w = density.a * box / ntry;
  for (double& v : tensor) v *= w;
}

SABLE_FIX("particletemplate/multisphere", FixParticletemplateMultisphere);

}  // namespace sable
