// The car's path seen from above, integrated from its rocker speeds: the model `seqc plot`
// prints on its picture and the preview animates. Speed units count as cm/s (x sideways, right
// positive; y forward) and z as degrees per second clockwise. The board's speeds are not
// calibrated to any unit, so the shape is right and the scale is nominal.
#pragma once

#include <vector>

#include "compiler/formats/raspblock_simulate.hpp"

namespace seqc::compiler {

struct CarPose {
  double x = 0, y = 0, heading = 0;  // cm right, cm forward (up), degrees clockwise from up
};

// One pose per sample of `sim`, starting at the origin facing up; each sample's speeds hold
// until the next sample.
std::vector<CarPose> car_path(const CarSimulation& sim);

}  // namespace seqc::compiler
