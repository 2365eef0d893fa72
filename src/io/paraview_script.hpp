// open_in_paraview.py, the paraview.simple script an output directory carries: it opens the run in
// ParaView coloured by displacement, with the rigid bodies in grey and the grid nodes hidden, finding
// the files beside itself (the folder can be moved).
#pragma once

#include <string>

namespace seismpm {

// The script's file name in an output directory.
inline constexpr const char* kParaViewScript = "open_in_paraview.py";

// What the script needs to know of the model: its dimension (2: a 2D view of the x-y plane) and the
// radius of the discs drawn for the deformable and the rigid particles (m: half their spacing).
struct ParaViewScriptSettings {
  int dim = 2;
  double particle_radius = 0.025;
  double rigid_radius = 0.025;
};

// The script's text (Python 3, ParaView 5.9 or later).
std::string paraview_script_text(const ParaViewScriptSettings& s);

}  // namespace seismpm
