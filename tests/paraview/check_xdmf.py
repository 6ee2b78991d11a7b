"""Opens a tmdem RESULT.xdmf with ParaView's three XDMF readers and checks what they show.

Run by tests/paraview/test_paraview_readers.cpp through pvbatch:
  pvbatch check_xdmf.py XDMF PARTICLES FRAMES LAST_TIME PARTICLE_ID TEMPERATURE CONTACTS WALLS [AT [WALL_Y [LONGEST]]]
XDMF must be an absolute path (ParaView's Xdmf3 readers resolve the .h5 next to it wrongly for
a bare file name). Exit 0 when every reader shows FRAMES time steps ending at LAST_TIME and, at
time AT (default LAST_TIME): PARTICLES points with the point arrays of the contract, particle
PARTICLE_ID at TEMPERATURE (K, to 1e-9 relative), CONTACTS contact lines with their cell arrays
(CONTACTS = 0: no contact grid, or one of 0 lines) and WALLS wall squares; with WALL_Y, one of
the squares lies in the plane y = WALL_Y (m, to 1e-12 m: a piston drawn where it is at AT; nan:
no check); with LONGEST, no contact line is longer than LONGEST (m: a periodic scene's contact
round a boundary drawn to the image beside it, not across the box).
"""
import sys

from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT, servermanager

path = sys.argv[1]
particles, frames = int(sys.argv[2]), int(sys.argv[3])
last_time, particle_id, temperature = float(sys.argv[4]), int(sys.argv[5]), float(sys.argv[6])
contacts, walls = int(sys.argv[7]), int(sys.argv[8])
check_time = float(sys.argv[9]) if len(sys.argv) > 9 else last_time
wall_y = float(sys.argv[10]) if len(sys.argv) > 10 and sys.argv[10] != "nan" else None
longest = float(sys.argv[11]) if len(sys.argv) > 11 else None


def leaves(data):
    """Every dataset leaf under a multiblock / multipiece tree."""
    if data is None:
        return []
    if data.IsA("vtkMultiBlockDataSet"):
        return [leaf for i in range(data.GetNumberOfBlocks()) for leaf in leaves(data.GetBlock(i))]
    if data.IsA("vtkMultiPieceDataSet"):
        return [leaf for i in range(data.GetNumberOfPieces()) for leaf in leaves(data.GetPiece(i))]
    return [data]


def point_arrays(data):
    return {data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())}


def cell_arrays(data):
    return {data.GetCellData().GetArrayName(i) for i in range(data.GetCellData().GetNumberOfArrays())}


def check(name, reader):
    problems = []
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    if len(times) != frames:
        problems.append(f"{len(times)} time steps, expected {frames}")
    if not times or abs(times[-1] - last_time) > 1e-9 * max(1.0, abs(last_time)):
        problems.append(f"last time {times[-1] if times else None}, expected {last_time}")
    if not any(abs(t - check_time) <= 1e-9 * max(1.0, abs(check_time)) for t in times):
        problems.append(f"no time step at {check_time}")
    reader.UpdatePipeline(check_time)
    found = leaves(servermanager.Fetch(reader))
    grains = [d for d in found if "id" in point_arrays(d)]
    lines = [d for d in found if "heat_flow" in cell_arrays(d)]
    squares = [d for d in found if d.GetNumberOfPoints() == 4 * walls and "temperature" in cell_arrays(d)]
    if len(grains) != 1:
        problems.append(f"{len(grains)} particle grids")
    else:
        g = grains[0]
        if g.GetNumberOfPoints() != particles:
            problems.append(f"{g.GetNumberOfPoints()} points, expected {particles}")
        missing = {"temperature", "velocity", "radius", "material", "id"} - point_arrays(g)
        if missing:
            problems.append(f"missing point arrays {sorted(missing)}")
        ids, T = g.GetPointData().GetArray("id"), g.GetPointData().GetArray("temperature")
        where = [k for k in range(g.GetNumberOfPoints()) if int(ids.GetValue(k)) == particle_id]
        if len(where) != 1:
            problems.append(f"particle {particle_id} found {len(where)} times")
        elif abs(T.GetValue(where[0]) - temperature) > 1e-9 * abs(temperature):
            problems.append(f"T[{particle_id}] = {T.GetValue(where[0])!r}, expected {temperature!r}")
    if contacts == 0:
        if any(d.GetNumberOfCells() > 0 for d in lines):
            problems.append("contact lines where there are none")
    else:
        if len(lines) != 1:
            problems.append(f"{len(lines)} contact grids")
        elif lines[0].GetNumberOfCells() != contacts:
            problems.append(f"{lines[0].GetNumberOfCells()} contact lines, expected {contacts}")
        elif {"normal_force", "conductance", "tangential_force"} - cell_arrays(lines[0]):
            problems.append("contact cell arrays missing")
        elif longest is not None:
            grid = lines[0]
            for c in range(grid.GetNumberOfCells()):
                ids = grid.GetCell(c).GetPointIds()
                a, b = grid.GetPoint(ids.GetId(0)), grid.GetPoint(ids.GetId(1))
                length = sum((a[k] - b[k]) ** 2 for k in range(3)) ** 0.5
                if length > longest:
                    problems.append(f"contact line {c} is {length!r} m long, longer than {longest!r}")
                    break
    if walls > 0 and len(squares) != 1:
        problems.append(f"{len(squares)} wall grids with {4 * walls} points")
    elif wall_y is not None:
        corners = [squares[0].GetPoint(k)[1] for k in range(4 * walls)]
        square_y = [corners[4 * q:4 * q + 4] for q in range(walls)]
        if not any(all(abs(y - wall_y) <= 1e-12 for y in ys) for ys in square_y):
            problems.append(f"no wall square at y = {wall_y!r}: {square_y}")
    print(f"{name}: {len(times)} time steps, at t = {check_time}: leaves "
          f"{[(d.GetNumberOfPoints(), d.GetNumberOfCells()) for d in found]}: "
          + ("ok" if not problems else "; ".join(problems)))
    return not problems


ok = True
ok &= check("Xdmf3ReaderS", Xdmf3ReaderS(FileName=[path]))
ok &= check("Xdmf3ReaderT", Xdmf3ReaderT(FileName=[path]))
ok &= check("XDMFReader", XDMFReader(FileNames=[path]))
sys.exit(0 if ok else 1)
