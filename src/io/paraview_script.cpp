#include "paraview_script.hpp"

#include <sstream>

namespace seismpm {

namespace {

// The script's header, before the settings.
constexpr const char* kHead =
    R"py(# Opens this seismpm run in ParaView: the particles coloured by displacement magnitude at the last
# output time (the colour range is that time's), the rigid bodies (rigid.pvd) in grey, the grid nodes
# (grid.pvd) loaded but hidden. Written by seismpm beside particles.pvd; the files are found beside
# this script, so the folder can be moved or copied as a whole.
#
#   paraview --script=open_in_paraview.py
#   pvpython open_in_paraview.py picture.png   (saves the picture; xvfb-run pvpython ... without a display)
#
# With SEISMPM_SCREENSHOT=picture.png in the environment, ParaView saves the picture and quits.
import os
import sys

from paraview.simple import *

)py";

// The rest, after the settings.
constexpr const char* kBody = R"py(

def run_folder():
    """This script's folder. ParaView's --script (and Python shell) gives the script no __file__: then
    the folder is found from the program's arguments (Linux) or the working directory."""
    here = globals().get("__file__")
    if here:
        return os.path.dirname(os.path.abspath(here))
    try:
        with open("/proc/self/cmdline", "rb") as f:
            args = [a.decode(errors="replace") for a in f.read().split(b"\0") if a]
    except OSError:
        args = []
    for arg in args + [os.getcwd()]:
        path = arg.split("=", 1)[1] if arg.startswith("--") and "=" in arg else arg
        if not (path.endswith(".py") or os.path.isdir(path)):
            continue
        folder = path if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))
        if os.path.isfile(os.path.join(folder, "particles.pvd")):
            return folder
    raise RuntimeError("open_in_paraview.py: cannot tell which folder this script is in; open it with "
                       "paraview --script=FOLDER/open_in_paraview.py, or start ParaView in that folder")


def show_points(source, view, radius):
    """Each particle a disc of the given radius (m): a filled look at any zoom."""
    display = Show(source, view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Plain circle"
    display.GaussianRadius = radius
    return display


folder = run_folder()
in_window = not sys.argv or not sys.argv[0]  # ParaView's window runs scripts with an empty argv
view = GetActiveViewOrCreate("RenderView")
if not in_window:
    view.ViewSize = [1200, 800]  # pvpython: the picture's size, so that text keeps its proportions
scene = GetAnimationScene()

particles = PVDReader(registrationName="particles", FileName=os.path.join(folder, "particles.pvd"))
scene.UpdateAnimationUsingDataTimeSteps()
try:
    last = float(list(particles.TimestepValues)[-1])
except (TypeError, IndexError):  # one file: a number, not a list
    last = float(particles.TimestepValues or 0.0)
scene.AnimationTime = last
particles.UpdatePipeline(last)
display = show_points(particles, view, PARTICLE_RADIUS)
if "displacement" in particles.PointData.keys():
    ColorBy(display, ("POINTS", "displacement", "Magnitude"))
    largest = particles.PointData["displacement"].GetRange(-1)[1]
    top = largest if largest > 0.0 else 1.0
    lut = GetColorTransferFunction("displacement")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(0.0, top)
    GetOpacityTransferFunction("displacement").RescaleTransferFunction(0.0, top)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "displacement (m)"
    bar.ComponentTitle = ""

if os.path.isfile(os.path.join(folder, "rigid.pvd")):
    rigid = PVDReader(registrationName="rigid", FileName=os.path.join(folder, "rigid.pvd"))
    rigid_display = show_points(rigid, view, RIGID_RADIUS)
    rigid_display.ColorArrayName = ["POINTS", ""]  # solid colour
    rigid_display.AmbientColor = [0.6, 0.6, 0.6]
    rigid_display.DiffuseColor = [0.6, 0.6, 0.6]
if os.path.isfile(os.path.join(folder, "grid.pvd")):
    grid = PVDReader(registrationName="grid", FileName=os.path.join(folder, "grid.pvd"))
    Hide(grid, view)

clock = AnnotateTime(registrationName="time")
clock.Format = "t = {time:.3f} s"
clock_display = Show(clock, view)
clock_display.WindowLocation = "Upper Left Corner"
SetActiveSource(particles)

if DIM == 2:
    view.InteractionMode = "2D"
    view.CameraPosition = [0.0, 0.0, 1.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.OrientationAxesVisibility = 0
view.ResetCamera()
Render(view)

picture = os.environ.get("SEISMPM_SCREENSHOT") or next((a for a in sys.argv[1:] if a.endswith(".png")), None)
if picture:
    SaveScreenshot(picture, view, ImageResolution=[1200, 800])
    if in_window:
        os._exit(0)  # inside ParaView's window: quit once the picture is saved
)py";

}  // namespace

std::string paraview_script_text(const ParaViewScriptSettings& s) {
  std::ostringstream os;
  os.precision(6);
  os << kHead << "DIM = " << s.dim << "  # the model's dimension: 2 gives a 2D view of the x-y plane\n"
     << "PARTICLE_RADIUS = " << s.particle_radius << "  # m: half the particle spacing\n"
     << "RIGID_RADIUS = " << s.rigid_radius << "  # m: the same for the rigid bodies' particles\n"
     << kBody;
  return os.str();
}

}  // namespace seismpm
