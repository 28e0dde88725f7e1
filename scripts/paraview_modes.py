"""Renders a squeal CEA run in ParaView: PNG frames of one period of its most
unstable mode (or a chosen one), warped and coloured by displacement, and the
preload's contact pressure on the pad faces when the run has a preload.

Run with ParaView's batch interpreter, off-screen through a virtual display
(scripts/paraview.sh does both):

    scripts/paraview.sh scripts/paraview_modes.py RUN_DIR OUT_DIR
        [--mode P,M] [--frames N] [--scale S] [--size W,H]

- RUN_DIR: a CEA run's result folder (modes.pvd and modes/, written with
  Output/Mode shapes other than none; preload/contact.pvd for a preloaded
  CEA);
- --mode P,M: sweep point P, mode M (the numbers in the mode files' names);
  default: the mode with the largest growth rate Re lambda;
- --frames N (default 24): frames over one period, phase 2 pi k / N; the
  displacement of frame k is Re[(mode_real + i mode_imag) e^(i 2 pi k/N)];
- --scale S (default 0.06): the largest displacement of the period drawn as
  S times the model's bounding-box diagonal.

Writes OUT_DIR/mode_frame_000.png ... and OUT_DIR/contact_pressure.png, and
prints what it drew. A missing or empty RUN_DIR, a run without mode shapes or
an unknown --mode stops it with one message and exit status 2.
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ElementTree

MODE_FILE = re.compile(r"mode_p(\d+)_m(\d+)_([-+0-9.eE]+)Hz_re([-+0-9.eE]+)_")


def fail(message):
    sys.stderr.write(f"paraview_modes.py: {message}\n")
    sys.exit(2)


def modes_of(run):
    """(point, mode, frequency [Hz], Re lambda [1/s], file) of each data set
    of run/modes.pvd."""
    pvd = os.path.join(run, "modes.pvd")
    if not os.path.isfile(pvd):
        fail(f"'{pvd}' does not exist: give a CEA result folder written with "
             "Output/Mode shapes other than none")
    out = []
    for ds in ElementTree.parse(pvd).getroot().iter("DataSet"):
        name = ds.get("file")
        m = MODE_FILE.search(os.path.basename(name))
        if m:
            out.append((int(m.group(1)), int(m.group(2)), float(m.group(3)),
                        float(m.group(4)), os.path.join(run, name)))
    if not out:
        fail(f"'{pvd}' lists no mode files")
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("run")
    parser.add_argument("out")
    parser.add_argument("--mode")
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--scale", type=float, default=0.06)
    parser.add_argument("--size", default="1200,800")
    args = parser.parse_args()
    if args.frames < 1 or not args.scale > 0:
        fail("--frames must be >= 1 and --scale > 0")
    size = [int(v) for v in args.size.split(",")]
    modes = modes_of(args.run)
    if args.mode:
        p, m = (int(v) for v in args.mode.split(","))
        chosen = [x for x in modes if x[0] == p and x[1] == m]
        if not chosen:
            fail(f"--mode {args.mode}: no such mode; the run has "
                 + ", ".join(f"{x[0]},{x[1]}" for x in modes[:20]))
        mode = chosen[0]
    else:
        mode = max(modes, key=lambda x: x[3])
    os.makedirs(args.out, exist_ok=True)

    from paraview import simple as pv  # noqa: E402 (needs pvbatch)

    reader = pv.OpenDataFile(mode[4])
    reader.UpdatePipeline()
    info = reader.GetDataInformation()
    bounds = info.GetBounds()
    diagonal = math.sqrt(sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2
                             for i in range(3)))
    arrays = reader.PointData.keys()
    if "mode_real" not in arrays or "mode_imag" not in arrays:
        fail(f"'{mode[4]}' has no mode_real/mode_imag point data")
    re_range = reader.PointData["mode_real"].GetRange(-1)
    im_range = reader.PointData["mode_imag"].GetRange(-1)
    peak = math.hypot(re_range[1], im_range[1])
    if not peak > 0:
        fail(f"'{mode[4]}': the mode shape is zero")
    view = pv.GetActiveViewOrCreate("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 1
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    calculator = pv.Calculator(Input=reader)
    calculator.ResultArrayName = "displacement"
    warp = pv.WarpByVector(Input=calculator)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = args.scale * diagonal / peak
    display = pv.Show(warp, view)
    pv.ColorBy(display, ("POINTS", "displacement", "Magnitude"))
    lut = pv.GetColorTransferFunction("displacement")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(0.0, peak)
    lut.AutomaticRescaleRangeMode = "Never"
    bar = pv.GetScalarBar(lut, view)
    bar.Title = "|u| (mode units)"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    display.SetScalarBarVisibility(view, True)
    view.CameraPosition = [1.0, -1.6, 1.3]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    pv.ResetCamera(view)
    text = pv.Text(Text=f"{mode[2]:.1f} Hz, Re lambda = {mode[3]:.3g} 1/s "
                   f"(point {mode[0]}, mode {mode[1]})")
    label = pv.Show(text, view)
    label.FontSize = 14
    label.Color = [0, 0, 0]
    for k in range(args.frames):
        phase = 2 * math.pi * k / args.frames
        calculator.Function = (f"{math.cos(phase):.17g}*mode_real-"
                               f"{math.sin(phase):.17g}*mode_imag")
        pv.Render(view)
        pv.SaveScreenshot(os.path.join(args.out, f"mode_frame_{k:03d}.png"),
                          view, ImageResolution=size)
    print(f"paraview_modes.py: {args.frames} frames of {mode[2]:.1f} Hz "
          f"(Re lambda {mode[3]:.4g} 1/s, point {mode[0]} mode {mode[1]}) "
          f"in {args.out}")

    contact = os.path.join(args.run, "preload", "contact.pvd")
    if os.path.isfile(contact):
        pv.Hide(warp, view)
        pv.Hide(text, view)
        surface = pv.OpenDataFile(contact)
        surface.UpdatePipeline(max(surface.TimestepValues or [0.0]))
        shown = pv.Show(surface, view)
        pv.ColorBy(shown, ("POINTS", "contact_pressure_Pa"))
        lut = pv.GetColorTransferFunction("contact_pressure_Pa")
        lut.ApplyPreset("Inferno (matplotlib)", True)
        shown.RescaleTransferFunctionToDataRange(True, False)
        shown.SetScalarBarVisibility(view, True)
        bar = pv.GetScalarBar(lut, view)
        bar.Title = "contact pressure [Pa]"
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        view.ViewTime = max(surface.TimestepValues or [0.0])
        view.CameraPosition = [0, 0, 1]
        view.CameraFocalPoint = [0, 0, 0]
        view.CameraViewUp = [0, 1, 0]
        pv.ResetCamera(view)
        pv.Render(view)
        pv.SaveScreenshot(os.path.join(args.out, "contact_pressure.png"),
                          view, ImageResolution=size)
        print(f"paraview_modes.py: preload contact pressure in {args.out}")


if __name__ == "__main__":
    main()
