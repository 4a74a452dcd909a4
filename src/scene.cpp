// Names of the scene's enumerations, exactly as a problem file spells them.
#include "latfrac/scene.h"

namespace latfrac {

const char* to_string(Criterion criterion) {
  switch (criterion) {
    case Criterion::tensile:
      return "tensile";
    case Criterion::tensile_or_shear:
      return "tensile_or_shear";
    case Criterion::elliptic:
      return "elliptic";
    case Criterion::drucker_prager:
      return "drucker_prager";
  }
  return "unknown";
}

const char* to_string(BondStress source) {
  switch (source) {
    case BondStress::strain:
      return "strain";
    case BondStress::tensor:
      return "tensor";
    case BondStress::critical_plane:
      return "critical_plane";
  }
  return "unknown";
}

const char* to_string(FaceCondition condition) {
  switch (condition) {
    case FaceCondition::free:
      return "free";
    case FaceCondition::roller:
      return "roller";
    case FaceCondition::fixed:
      return "fixed";
    case FaceCondition::extension:
      return "extension";
  }
  return "unknown";
}

const char* to_string(Face face) {
  switch (face) {
    case Face::x_min:
      return "x_min";
    case Face::x_max:
      return "x_max";
    case Face::y_min:
      return "y_min";
    case Face::y_max:
      return "y_max";
    case Face::z_min:
      return "z_min";
    case Face::z_max:
      return "z_max";
  }
  return "unknown";
}

}  // namespace latfrac
