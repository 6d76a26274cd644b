"""scripts/paraview_scene.py - the beam and its stops from a gapbeam XDMF file, in ParaView.

Usage (pvpython, ParaView 5.11 or later: Debian/Ubuntu `apt-get install python3-paraview`;
without a display, under xvfb: `apt-get install xvfb`):

  xvfb-run -a pvpython scripts/paraview_scene.py PREFIX.xdmf [--out shot.png] [--time T | --peak]
      [--scale S] [--size WxH] [--reader xdmf3|legacy] [--frames DIR]

Opens PREFIX.xdmf (written beside PREFIX.h5 by a transient run with `&output state_history`),
warps beam and stops by the vector "displacement [m]" with the scale factor S (default: the one
the file's header suggests, which keeps the largest |w| within a quarter of the span; 1 is true
scale), draws the beam as a thick blue line from its root (a grey block at x = 0) and each
stop as a block (a circular stop as its circle), grey while open and red while it pushes on
the beam (cell field "contact [1 closed, 0
open]"), looks at the (x, w) plane with a parallel projection fitted to the span and the swing,
and writes a PNG of one time: T [s] (absolute simulation time, as /history/time), or with
--peak (the default) the sample where the stop force is largest: the beam meeting its stop.
--frames DIR writes one PNG per history sample instead (an animation: e.g. `ffmpeg -i
DIR/frame_%05d.png beam.mp4`). The label in the corner gives the time, the stop force and the
scale. In the ParaView GUI the same scene is: File > Open (either XDMF reader), Filters > Warp
By Vector (Vectors "displacement [m]", Scale Factor S), colour by "contact [1 closed, 0 open]",
view along -z (the "-Z" button), play (docs/outputs.md, ParaView).

Exit status 0; 1 when the file cannot be read or has no beam; 2 on a usage error.
"""

import argparse
import os
import re
import sys

from paraview import servermanager as sm
from paraview import simple as pv

FORCE = "stop force [N]"
CONTACT = "contact [1 closed, 0 open]"
DISP = "displacement [m]"


def header(path):
    """The suggested scale, the largest |w| [m] and the span [m] from the file's header."""
    with open(path, encoding="utf-8") as f:
        head = f.read(4000)
    m = re.search(r"scale factor ([0-9.eE+-]+) keeps the largest \|w\| = ([0-9.eE+-]+) m "
                  r"within a quarter of the span ([0-9.eE+-]+) m", head)
    if not m:
        return 1.0, 0.0, 0.0
    return float(m.group(1)), float(m.group(2)), float(m.group(3))


def leaves(data):
    """The leaf datasets of a composite (multiblock, multipiece) dataset, or the dataset."""
    if data is None:
        return []
    if not data.IsA("vtkCompositeDataSet"):
        return [data]
    out = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        out.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return out


def stop_force_at(reader, t):
    """The largest stop force [N] at time t (0 when the file has no stops)."""
    reader.UpdatePipeline(t)
    best = 0.0
    for b in leaves(sm.Fetch(reader)):
        a = b.GetCellData().GetArray(FORCE)
        if a is not None and a.GetNumberOfTuples() > 0:
            best = max(best, a.GetTuple1(0))
    return best


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("xdmf")
    p.add_argument("--out", default="beam.png")
    p.add_argument("--time", type=float, default=None)
    p.add_argument("--peak", action="store_true")
    p.add_argument("--scale", type=float, default=None)
    p.add_argument("--size", default="900x420")
    p.add_argument("--reader", choices=("xdmf3", "legacy"), default="xdmf3")
    p.add_argument("--frames", default=None)
    a = p.parse_args(argv[1:])
    try:
        width, height = (int(v) for v in a.size.lower().split("x"))
    except ValueError:
        p.error("--size: expected WxH, e.g. 900x420")
    suggested, swing, span = header(a.xdmf)
    scale = a.scale if a.scale is not None else suggested

    if a.reader == "xdmf3":
        reader = pv.Xdmf3ReaderS(FileName=[a.xdmf])
    else:
        reader = pv.XDMFReader(FileNames=[a.xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues or [])
    if not times:
        print("paraview_scene: {}: no time steps".format(a.xdmf), file=sys.stderr)
        return 1
    if a.time is not None:
        t_show = min(times, key=lambda t: abs(t - a.time))
    else:
        forces = [stop_force_at(reader, t) for t in times]
        t_show = times[max(range(len(times)), key=lambda i: forces[i])]

    warp = pv.WarpByVector(Input=reader)
    warp.Vectors = ["POINTS", DISP]
    warp.ScaleFactor = scale
    view = pv.CreateRenderView()
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    # the beam (the blocks with the point field w) and the stops (those with the contact
    # state), each its own display
    beam = pv.Threshold(Input=warp)
    beam.Scalars = ["POINTS", "w [m]"]
    beam.LowerThreshold, beam.UpperThreshold = -1.0e30, 1.0e30
    beam_shown = pv.Show(beam, view)
    pv.ColorBy(beam_shown, None)
    beam_shown.AmbientColor = beam_shown.DiffuseColor = [0.12, 0.31, 0.61]
    beam_shown.LineWidth = 5.0
    beam_shown.RenderLinesAsTubes = 1
    stops = pv.Threshold(Input=warp)
    stops.Scalars = ["CELLS", CONTACT]
    stops.LowerThreshold, stops.UpperThreshold = -1.0, 2.0
    stops_shown = pv.Show(stops, view)
    stops_shown.LineWidth = 4.0
    pv.ColorBy(stops_shown, ("CELLS", CONTACT))
    lut = pv.GetColorTransferFunction(CONTACT)
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = ["0", "stop open", "1", "stop closed (contact)"]
    lut.IndexedColors = [0.62, 0.62, 0.62, 0.85, 0.1, 0.1]
    stops_shown.SetScalarBarVisibility(view, False)

    # the root (the clamp moving with the base) as a grey block behind x = 0
    span0 = span if span > 0 else 0.2
    root = pv.Box(XLength=0.02 * span0, YLength=0.16 * span0, ZLength=0.001 * span0,
                  Center=[-0.01 * span0, 0.0, 0.0])
    root_shown = pv.Show(root, view)
    root_shown.AmbientColor = root_shown.DiffuseColor = [0.55, 0.55, 0.55]

    label = pv.Text()
    label_shown = pv.Show(label, view)
    label_shown.FontSize = 14
    label_shown.Color = [0.1, 0.1, 0.1]
    label_shown.WindowLocation = "Upper Left Corner"
    label_shown.Justification = "Left"

    # the (x, w) plane, parallel projection, the span and the warped swing in view (after a
    # first render: paraview.simple resets the camera on a view's first render)
    pv.Render(view)
    span = span if span > 0 else 0.2
    reach = max(scale * swing, 0.05 * span) * 1.35
    view.CameraPosition = [0.49 * span, 0.0, 10.0 * span]
    view.CameraFocalPoint = [0.49 * span, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = max(reach, 0.56 * span * height / width)

    def render(t, path):
        view.ViewTime = t
        label.Text = "t = {:.4f} s   stop force {:.3f} N   warp scale {:g}\nblue: beam " \
                     "(relative to the base), red: a stop in contact, grey: open".format(
                         t, stop_force_at(reader, t), scale)
        pv.Render(view)
        pv.SaveScreenshot(path, view, ImageResolution=[width, height])

    if a.frames:
        os.makedirs(a.frames, exist_ok=True)
        for i, t in enumerate(times):
            render(t, os.path.join(a.frames, "frame_{:05d}.png".format(i)))
        print("paraview_scene: wrote {} frames to {}".format(len(times), a.frames))
    else:
        render(t_show, a.out)
        print("paraview_scene: wrote {} (t = {:.6f} s, warp scale {:g})".format(
            a.out, t_show, scale))
    return 0


if __name__ == "__main__":
    status = main(sys.argv)
    # leave without ParaView's teardown: under xvfb with Mesa it fails at exit ("X Error of
    # failed request: GLXBadContext", exit status 1) after the images are written
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)
