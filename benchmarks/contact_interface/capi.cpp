// A C interface to OpenSees's SoilFootingSection2d (Gajan and Kutter's contact interface
// model), compiled beside the section's own source from an OpenSees tree against the stand-ins
// in shim/ (benchmarks/contact_interface.py): create, set a trial deformation, read the
// section's force and tangent, commit, and read its footing and soil surface (for the gap
// under the edges, which the class keeps but does not expose).
//
// The object is built in zeroed memory: the class's bounding surface reads a member (h) that
// its constructor never sets, so the same run gives the same numbers.
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <new>

#include "ID.h"
#include "Matrix.h"
#include "OPS_Stream.h"
#include "SectionForceDeformation.h"
#include "Vector.h"

#define private public
#define protected public
#include <SoilFootingSection2d.h>
#undef private
#undef protected

OPS_Stream opserr;

extern "C" {

void *cim_new(double fs, double vult, double length, double kv, double kh, double rv,
              double segment) {
  void *memory = std::calloc(1, sizeof(SoilFootingSection2d));
  if (memory == nullptr) return nullptr;
  return new (memory) SoilFootingSection2d(1, fs, vult, length, kv, kh, rv, segment);
}

void cim_delete(void *handle) {
  SoilFootingSection2d *section = static_cast<SoilFootingSection2d *>(handle);
  section->~SoilFootingSection2d();
  std::free(handle);
}

// Set the trial deformation (v down, u, theta) and write the force (V, H, M) and the 3 x 3
// tangent (row-major) the section then returns.
int cim_trial(void *handle, const double *deformation, double *force, double *tangent) {
  SoilFootingSection2d *section = static_cast<SoilFootingSection2d *>(handle);
  Vector e(3);
  for (int i = 0; i < 3; i++) e(i) = deformation[i];
  int status = section->setTrialSectionDeformation(e);
  const Vector &s = section->getStressResultant();
  const Matrix &k = section->getSectionTangent();
  for (int i = 0; i < 3; i++) {
    force[i] = s(i);
    for (int j = 0; j < 3; j++) tangent[3 * i + j] = k(i, j);
  }
  return status;
}

// The section's initial tangent (row-major), what OpenSees's initial-stiffness options use.
void cim_initial_tangent(void *handle, double *tangent) {
  const Matrix &k = static_cast<SoilFootingSection2d *>(handle)->getInitialTangent();
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) tangent[3 * i + j] = k(i, j);
}

int cim_commit(void *handle) {
  return static_cast<SoilFootingSection2d *>(handle)->commitState();
}

// The number of points along the footing (noNodes + 1).
int cim_points(void *handle) {
  return static_cast<SoilFootingSection2d *>(handle)->noNodes + 1;
}

// The footing's and the soil surface's positions (down) at each point, at the last trial.
void cim_contact(void *handle, double *footing, double *surface) {
  SoilFootingSection2d *section = static_cast<SoilFootingSection2d *>(handle);
  for (int i = 0; i <= section->noNodes; i++) {
    footing[i] = section->foot[i][0];
    surface[i] = section->soilMin[i][0];
  }
}
}
