// The commands are thin layers over the evaluation library (eval/, namespace fovea::eval): its
// names (ReferenceSource, FrameErrors, BenchSpec, OutputFolder, ...) are used in the commands as
// if they were their own.
#pragma once

namespace fovea::eval {}

namespace fovea::app {
using namespace fovea::eval;
}  // namespace fovea::app
