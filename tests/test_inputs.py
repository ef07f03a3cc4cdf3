"""Bad input gets a clear error before any work starts: it names the field, the value and the
valid range. Also the readers, scenes and result files that guard the inputs and outputs."""

import json
import math
import os
import re

import numpy as np
import pytest

from upliftlab.checks import InputError
from upliftlab.cli import main as cli
from upliftlab.motions import (Motion, cosine_pulse, find_motion, free_vibration, harmonic,
                               load_motion, read_motion, ricker_pulse, sine_pulse)
from upliftlab.reduced import run
from upliftlab.results import read_dataset, read_netcdf, write_netcdf
from upliftlab.scenes import load_scene, packaged_scenes

BAD_FIELDS = [
    ("structure.weight=0", "structure.weight = 0: outside the physical range [2.25e-10, "
                           "2.25e+09] kip ([1e-06, 1e+13] N)"),
    ("structure.weight=-5", "structure.weight = -5: outside the physical range"),
    ("structure.weight=1e300", "structure.weight = 1e+300: outside the physical range"),
    ("structure.stiffness=-1", "structure: give stiffness or period, not both"),
    ("foundation.stiffness=0", "foundation: give stiffness or vertical_period, not both"),
    ("foundation.vertical_period=0", "foundation.vertical_period = 0: outside the physical "
                                     "range [1e-05, 1e+04] s"),
    ("foundation.springs=100001", "foundation.springs = 100001: valid range is [2, 100000]"),
    ("foundation.restitution=1.2", "foundation.restitution = 1.2: valid range is [0, 1]"),
    ("foundation.restitution=-0.1", "foundation.restitution = -0.1: valid range is [0, 1]"),
    ("foundation.yield_multiple=1.0", "foundation.yield_multiple = 1: valid range is (1, 1e+06]"),
    ("foundation.springs=1", "foundation.springs = 1: must be an integer >= 2"),
    ("foundation.springs=2.5", "foundation.springs = 2.5: expected an integer >= 2"),
    ("foundation.law='plastic'", "foundation.law = 'plastic': must be one of"),
    ("foundation.z50=0.5", "foundation.z50 is read only with foundation.law = 'qz' (law is "
                           "'elastoplastic'); remove it or set the law"),
    ("foundation.yield_forces=[1.0, 2.0]", "foundation.yield_multiple with "
                                           "foundation.yield_forces: each sets the"),
    ("foundation.colour='red'", "foundation.colour: unknown key"),
    ("units='furlong-stone-fortnight'", "units = 'furlong-stone-fortnight': must be one of"),
    ("analysis.integrator='euler'", "analysis.integrator = 'euler': must be one of"),
    ("structure.damping_ratio=1.5", "structure.damping_ratio = 1.5: valid range is [0, 1]"),
    ("structure.rotary_inertia=0", "structure.rotary_inertia = 0: the rocking base needs"),
    ("motion.velocity=nan", "motion.velocity = nan: expected a finite number"),
]


@pytest.mark.parametrize("override, message", BAD_FIELDS)
def test_bad_scene_fields_are_named_with_their_range(override, message):
    with pytest.raises(InputError) as err:
        load_scene("short_period_free", case="B", overrides=[override])
    assert message in str(err.value)


def test_every_packaged_scene_loads_and_every_case_validates():
    for name in packaged_scenes():
        scene = load_scene(name)
        for case in scene.cases:
            load_scene(name, case=case)


def test_unknown_case_and_scene_are_errors():
    with pytest.raises(InputError, match="case = 'Z': not defined in this scene"):
        load_scene("short_period_free", case="Z")
    with pytest.raises(InputError, match="no such file, and no packaged scene"):
        load_scene("no_such_scene")


def test_overrides_address_nested_keys_and_remove_keys():
    scene = load_scene("short_period_free", overrides=["foundation.springs=40",
                                                       "structure.period=0.3"])
    assert scene.foundation.springs == 40
    mass = 202.0 / 386.09
    assert scene.structure.stories[0].stiffness == pytest.approx(mass * (2 * math.pi / 0.3) ** 2)
    with pytest.raises(InputError, match="foundation.stiffness is missing"):
        load_scene("short_period_free", overrides=["foundation.vertical_period="])


def test_time_step_beyond_stability_is_refused_with_the_limit():
    """The message carries the limit; subcycling on request runs at a stable step instead."""
    scene = load_scene("short_period_free", case="A", overrides=["motion.duration=0.2"])
    with pytest.raises(InputError, match=r"analysis.dt = 0.5 s is beyond the stability limit "
                                         r"[0-9.e-]+ s of integrator 'rk4'"):
        run(scene, integrator="rk4", dt=0.5)
    sub = scene.with_overrides("analysis.subcycle=true")
    response = run(sub, integrator="rk4", dt=0.05)
    assert response.info["dt"] <= response.info["stability_limit"]
    assert "subcycled" in response.info["step_choice"]


def test_motion_files_two_columns_one_column_and_at2(tmp_path):
    t = np.arange(50) * 0.01
    a = 0.1 * np.sin(2 * np.pi * t)
    two = tmp_path / "two.txt"
    two.write_text("# time [s], acc [g]\n" + "\n".join(f"{x:.2f} {y:.6f}" for x, y in zip(t, a)))
    one = tmp_path / "one.txt"
    one.write_text("\n".join(f"{y:.6f}" for y in a))
    at2 = tmp_path / "rec.AT2"
    body = "\n".join(" ".join(f"{y:.6E}" for y in a[i:i + 5]) for i in range(0, 50, 5))
    at2.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nTEST\nACCELERATION TIME SERIES IN "
                   f"UNITS OF G\nNPTS=   50, DT=   .0100 SEC\n{body}\n")
    for motion in (read_motion(two), read_motion(one, dt=0.01), read_motion(at2)):
        assert motion.dt == pytest.approx(0.01)
        np.testing.assert_allclose(motion.acceleration, a, atol=1e-6)
    assert read_motion(two).scaled_to_pga(0.3).pga == pytest.approx(0.3)



def test_a_motion_file_is_parsed_once_and_reread_when_it_changes(tmp_path):
    # Reference: the file's own samples. read_motion caches a parsed file by its path, size
    # and modification time: the same file gives the same (immutable) record, and a rewritten
    # file is read again, never served stale.
    path = tmp_path / "rec.txt"
    path.write_text("0.00 0.1\n0.01 0.2\n0.02 0.3\n")
    first = read_motion(path)
    assert read_motion(path) is first
    assert not first.acceleration.flags.writeable
    path.write_text("0.00 0.5\n0.01 0.6\n0.02 0.7\n")
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))  # a later write
    np.testing.assert_allclose(read_motion(path).acceleration, [0.5, 0.6, 0.7], rtol=1e-15)
    np.testing.assert_allclose(first.acceleration, [0.1, 0.2, 0.3], rtol=1e-15)

@pytest.mark.parametrize("content, message", [
    ("0.0 0.1\n0.01 nan\n", "line 2: value nan is not a finite number"),
    ("0.0 0.1\n0.01 0.2\n0.03 0.1\n", r"line 2: time step 0\.01 s \(from the row before\) "
                                     r"differs from the file's typical step 0\.015 s"),
    # a repeated time is named on its own row, line 3, not on the step before it (line 2);
    # a time that goes back, likewise; the comment line does not shift the numbering
    ("0.0 0.1\n0.02 0.2\n0.02 0.3\n", r"line 3: time 0\.02 s does not increase \(the row"),
    ("# t a\n0.0 0.1\n0.02 0.2\n0.04 0.3\n0.03 0.1\n", r"line 5: time 0\.03 s does not increase"),
    ("0.0 0.1 0.3\n0.01 0.2 0.4\n", "3 columns; expected 2"),
    ("0.0 0.1\n0.01\n", "line 2: 1 columns, but the first data row has 2"),
    ("0.0 abc\n", "is not numbers"),
])
def test_bad_motion_files_are_refused(tmp_path, content, message):
    path = tmp_path / "bad.txt"
    path.write_text(content)
    with pytest.raises(InputError, match=message):
        read_motion(path)


def _rows(times) -> str:
    """A two-column record of ``times`` (s), 0.1 g throughout, one row a line."""
    return "".join(f"{t} 0.1\n" for t in times)


TIMES = [round(0.02 * k, 2) for k in range(100)]  # 100 rows at 0.02 s: 0 to 1.98 s


@pytest.mark.parametrize("times, line, step", [
    (TIMES[:50] + TIMES[51:], 51, "0.04"),  # line 51 (1.02 s) follows line 50 (0.98 s)
    (TIMES[:-1] + [2.50], 100, "0.54"),     # the last row's time mistyped
    ([0, 0.02, 0.05, 0.07], 3, "0.03"),     # the odd step ends on line 3
])
def test_an_odd_time_step_is_named_on_its_own_line(times, line, step, tmp_path):
    """The line of the first row whose step differs from the file's typical (median) step.
    Measured from the mean step, (t_last - t_first)/(n - 1), one bad row anywhere made every
    step differ, and the message named line 2. An accepted file's step is still that mean."""
    path = tmp_path / "bad.txt"
    path.write_text(_rows(times))
    with pytest.raises(InputError, match=re.escape(
            f"'{path}' line {line}: time step {step} s (from the row before) differs from the "
            "file's typical step 0.02 s (the median of its steps)")):
        read_motion(path)
    jittered = tmp_path / "jittered.txt"  # steps within the 1e-6 tolerance of uniform
    times = [0.02 * k + 6e-9 * (-1) ** k for k in range(100)]
    jittered.write_text(_rows(f"{t!r}" for t in times))
    assert read_motion(jittered).dt == (times[-1] - times[0]) / 99


AT2_HEAD = "PEER NGA\nx\nACCELERATION TIME SERIES IN UNITS OF G\n"


@pytest.mark.parametrize("content, message", [
    # a form feed on a line of its own, then a bad row on line 4 (not 5)
    ("0 0.1\n\f\n0.02 0.2\n0.04 x\n", "line 4: '0.04 x' is not numbers"),
    # \x85, \u2028 and a form feed in a comment are the comment's, not line breaks
    ("# a\x85b\u2028c\fd\n0 0.1\n0.02 0.2\n0.04 x\n", "line 4: '0.04 x' is not numbers"),
    ("# comment\fwith form feed\n0 0.1\n0.02 0.2\n0.04 0.1\n0.07 0\n",
     "line 5: time step 0.03 s"),
    # a line break is \n, \r\n or \r alone
    ("0 0.1\r\n0.02 0.2\r0.04 x\n", "line 3: '0.04 x' is not numbers"),
    # in a PEER record: a title with a form feed and \x1c; a sample on line 6 that is nan
    (AT2_HEAD.replace("x", "x\fy\x1cz") + "NPTS=   6, DT=   .0100 SEC\n0.1 0.2 0.3\nnan 0.1 0.2\n",
     "line 6: value nan is not a finite number"),
])
def test_lines_are_counted_as_an_editor_counts_them(content, message, tmp_path):
    """``str.splitlines`` also breaks lines at \\f, \\v, \\x1c-\\x1e, \\x85, \\u2028 and
    \\u2029: messages named a line too far on, and a comment went on as a data line."""
    path = tmp_path / ("bad.AT2" if content.startswith("PEER") else "bad.txt")
    path.write_bytes(content.encode())
    with pytest.raises(InputError, match=re.escape(f"'{path}' {message}")):
        read_motion(path)


@pytest.mark.parametrize("body, message", [
    ("NPTS=   6, DT=   .0100 SEC\n0.1 0.2 0.3\n0.4 nan 0.2\n",
     "line 6: value nan is not a finite number"),
    ("NPTS=   7, DT=   .0100 SEC\n0.1 0.2 0.3\n0.4 0.5 0.2\n",
     "line 4: the header says NPTS=7 but lines 5-6 hold 6 values"),
    ("NPTS=   3, DT=   1E-300 SEC\n0.1 0.2 0.3\n",
     "line 4: DT = 1e-300: valid range is [1e-09, 1000]"),
])
def test_a_peer_records_faults_name_their_line(body, message, tmp_path):
    """A nan sample was named by its 0-based sample number ('value 4'), a count that does not
    match NPTS and a DT of 1e-300 s by no line (the last as 'motion.dt', a field not set)."""
    path = tmp_path / "bad.AT2"
    path.write_text(AT2_HEAD + body)
    with pytest.raises(InputError, match=re.escape(f"motion file '{path}' {message}")):
        read_motion(path)


def test_a_records_own_values_out_of_range_name_the_file(tmp_path, monkeypatch, capsys):
    """A record with 1e300 g on line 3 was refused as 'motion.scale = 1: the scaled record's PGA
    would be 1e+300 g', a field never set; a step of 1e-300 s as 'motion.dt = 1e-300'. Each now
    names the file and its line; a scale that takes a record beyond 100 g is still blamed."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "big.txt").write_text("# g\n0 0.1\n0.02 -1e300\n0.04 0.2\n")
    (tmp_path / "tiny.txt").write_text("0 0.1\n1e-300 0.2\n2e-300 0.1\n")
    (tmp_path / "fine.txt").write_text("0 0.1\n0.02 -60\n0.04 0.2\n")
    run = ["run", "wall_free", "--case", "e07", "--no-figure", "--out", "o"]
    for argv, words in (
            (["big.txt"], f"motion file '{tmp_path / 'big.txt'}' line 3: acceleration -1e+300 "
                          "g, the record's peak; valid: a PGA up to 100 g"),
            (["tiny.txt"], "motion file 'tiny.txt' line 2: the file's time step dt = 1e-300: "
                           "valid range is [1e-09, 1000]"),
            (["fine.txt", "--set", "motion.scale=2"], "motion.scale = 2: the scaled record's "
                                                      "PGA would be 120 g")):
        assert cli([*run, "--motion", *argv]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith(f"upliftlab: error: {words}"), err
        assert not (tmp_path / "o").exists()


# a device: /dev/null, not /dev/zero, so that code which opened it would read nothing, not fill
# the memory (the old --macro-calibration read /dev/zero until the kernel killed it)
@pytest.mark.parametrize("given, kind", [
    ("m/adir", "a folder"), ("m/fifo.txt", "a named pipe"), ("/dev/null", "a character device"),
])
def test_a_motion_path_that_is_not_a_regular_file_says_what_it_is(given, kind, tmp_path,
                                                                  monkeypatch, capsys, fifo):
    """A folder, a named pipe or a device was refused as 'does not exist'; a named pipe is
    never opened (it would wait for a writer)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "m" / "adir").mkdir(parents=True)
    fifo("m/fifo.txt")
    assert cli(["run", "wall_free", "--case", "e07", "--no-figure", "--motion", given,
                "--out", "o"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"upliftlab: error: motion file '{given}' is {kind}, not a regular file; "
                   "give a record file (two columns, one column with motion.dt, or PEER .AT2)"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m"]


def test_a_scene_path_that_is_a_named_pipe_says_so(tmp_path, monkeypatch, capsys, fifo):
    """A scene path that is a named pipe was refused as 'no such file' (a folder already said
    it was one); it is never opened."""
    monkeypatch.chdir(tmp_path)
    fifo("m/s.toml")
    assert cli(["run", "m/s.toml", "--no-figure", "--out", "o"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("upliftlab: error: scene 'm/s.toml': a named "
                                               "pipe, not a scene file; a path is used as "
                                               "given"), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m"]


def test_one_column_needs_dt_and_missing_names_say_how_to_supply(tmp_path, monkeypatch):
    path = tmp_path / "one.txt"
    path.write_text("0.1\n0.2\n")
    with pytest.raises(InputError, match="has one column: give its dt"):
        read_motion(path)
    monkeypatch.setenv("UPLIFTLAB_MOTIONS", str(tmp_path))
    with pytest.raises(InputError, match="set UPLIFTLAB_MOTIONS to the directory that holds "
                                         "elcentro_1940_ns.txt \\(El Centro 1940 N-S"):
        load_motion("elcentro_1940_ns")


def test_builtin_motions():
    """Pulses and harmonics in g: amplitude, period and length as asked."""
    sine = sine_pulse(0.3, 0.5, 1.0, dt=0.001)
    assert sine.pga == pytest.approx(0.3, rel=1e-5)
    assert np.all(sine.acceleration_at(np.array([0.6, 1.0])) == 0.0)
    assert cosine_pulse(0.2, 0.5, dt=0.001).acceleration[0] == pytest.approx(0.2)
    ricker = ricker_pulse(0.4, 0.5, dt=0.001)
    assert ricker.pga == pytest.approx(0.4, rel=1e-6)
    assert harmonic(0.1, 0.25, 2.0, dt=0.005).duration == pytest.approx(2.0)
    with pytest.raises(InputError, match="free vibration needs a nonzero"):
        free_vibration(1.0)
    with pytest.raises(InputError, match="acceleration sample 1 is nan"):
        Motion("x", 0.01, [0.0, np.nan])


def test_netcdf_results_are_self_describing_and_read_by_xarray(tmp_path):
    # Reference: the CF-1.10 conventions and the NetCDF-4 format (an HDF5 file, its arrays
    # deflated), checked with h5py independently of xarray; the values round-trip exactly.
    import h5py
    scene = load_scene("short_period_free", case="C", overrides=["motion.duration=0.5"])
    response = run(scene)
    path = response.save(tmp_path / "run.nc", csv=True)[0]
    assert path.read_bytes()[:8] == b"\x89HDF\r\n\x1a\n"  # NetCDF-4 is HDF5
    with h5py.File(path) as h5:
        assert h5["spring_force"].compression == "gzip" and h5["spring_force"].shuffle
    ds = read_dataset(path)  # xarray's reader, the CF time axis and labels as in memory
    np.testing.assert_array_equal(ds["u"].values, response.u)
    np.testing.assert_array_equal(ds.spring_force.sel(spring=3).values, response.force[:, 3])
    np.testing.assert_array_equal(ds.q.sel(dof="theta").values, response.theta)
    assert ds.attrs["Conventions"] == "CF-1.10" and ds["u"].attrs["units"] == "in"
    for name, var in ds.variables.items():
        assert var.attrs.get("long_name"), name
        if var.dtype.kind == "f" and name not in ("q", "qd"):
            assert var.attrs.get("units"), name
    # the DOFs are lengths and a rotation: no one unit; each DOF's is a coordinate
    assert ds.dof_units.values.tolist() == ["in", "rad", "in"]
    assert "dof_units" in ds.q.attrs["comment"] and "dof_units" in ds.qd.attrs["comment"]
    assert ds["spring_mode"].attrs["flag_meanings"].split() == [
        "separated", "contact", "yielding", "clipped"]
    assert ds["peak_u"].item() == response.peaks["u"] and ds["peak_u"].attrs["units"] == "in"
    assert ds.attrs["provenance_scene"] == "short_period_free-C"
    assert ds.attrs["provenance_model"] == "reduced"
    assert len(ds.attrs["provenance_source_sha256"]) == 64
    assert ds.attrs["provenance_numba"] and ds.attrs["provenance_scipy"]
    assert len(ds.attrs["info_motion_sha256"]) == 64
    # the motion the run read is in the file: the free vibration's record is all zeros, so
    # check its length and time axis against the run's duration
    assert ds.record_time.values[-1] <= 0.5 + 1e-12 and ds.ground_acceleration.size >= 2
    ds.close()
    assert (tmp_path / "run.csv").read_text().splitlines()[2].startswith("time,u,x,theta")


def test_a_records_samples_are_in_its_result_file(tmp_path, elcentro):
    # Reference: the record's file read with numpy alone (columns time [s], acceleration [g]),
    # in g after dividing by g in the scene's units (386.09 in/s²).
    import xarray as xr
    response = run(load_scene("short_period_elcentro", case="B",
                              overrides=["motion.duration=1.0"]))
    ds = xr.open_dataset(response.save(tmp_path / "run.nc")[0], engine="h5netcdf")
    recorded = ds.ground_acceleration.values / 386.09
    assert ds.ground_acceleration.attrs["units"] == "in/s^2"
    assert recorded.size == 50 and ds.record_time.values[1] == pytest.approx(0.02, rel=1e-12)
    first_second = np.loadtxt(find_motion("elcentro_1940_ns"))[:50, 1]
    assert np.abs(recorded - first_second).max() <= 1e-12
    ds.close()


def test_results_are_written_atomically(tmp_path):
    """A failed write leaves no partial file and keeps the old one."""
    path = tmp_path / "r.nc"
    write_netcdf(path, {"a": (("n",), np.arange(3.0), {})})
    before = path.read_bytes()
    with pytest.raises(ValueError):
        write_netcdf(path, {"a": (("n",), np.arange(3.0), {}),
                            "b": (("n",), np.arange(4.0), {})})
    assert path.read_bytes() == before
    assert not list(tmp_path.glob("*.part"))
    assert read_netcdf(path)[0]["a"].tolist() == [0.0, 1.0, 2.0]
    umask = os.umask(0o022)
    os.umask(umask)
    assert path.stat().st_mode & 0o777 == 0o666 & ~umask  # an ordinary file's mode, not 0o600


def test_cli_refuses_bad_input_before_writing(tmp_path, capsys):
    out = tmp_path / "out"
    code = cli(["run", "wall_free", "--set", "foundation.restitution=2", "--out", str(out)])
    assert code == 2
    assert "foundation.restitution = 2: valid range is [0, 1]" in capsys.readouterr().err
    assert not out.exists()


def test_cli_run_json_summary(tmp_path, capsys):
    code = cli(["run", "short_period_free", "--case", "A", "--set", "motion.duration=1.0",
                "--out", str(tmp_path), "--json", "--no-figure"])
    assert code == 0
    summary = json.loads(capsys.readouterr().out)
    response = run(load_scene("short_period_free", case="A",
                              overrides=["motion.duration=1.0"]))
    assert summary["peak_u"] == pytest.approx(response.peaks["u"], rel=1e-12)
    assert summary["peak_uplift_left"] == pytest.approx(response.peaks["uplift_left"], rel=1e-12)
    assert (tmp_path / "short_period_free-A.nc").exists()


def test_paper_without_the_record_makes_free_vibration_figures(tmp_path, monkeypatch, capsys):
    """Without El Centro: Figs. 4, 7 and 9, and the summary says what to supply and how."""
    monkeypatch.setenv("UPLIFTLAB_MOTIONS", str(tmp_path / "empty"))
    code = cli(["paper", "--out", str(tmp_path / "paper")])
    assert code == 0
    summary = json.loads((tmp_path / "paper" / "summary.json").read_text())
    assert summary["figures"] == [4, 7, 9]
    assert summary["missing_figures"] == [5, 8, 10, 11, 12]
    text = (tmp_path / "paper" / "summary.md").read_text()
    assert "elcentro_1940_ns.txt" in text and "UPLIFTLAB_MOTIONS" in text and "--motion" in text
    assert "El Centro" in capsys.readouterr().out
    for n in (4, 7, 9):
        assert (tmp_path / "paper" / f"fig{n:02d}.png").stat().st_size > 10_000


@pytest.mark.parametrize("key, value, shown", [
    # a NUL in the title was found only when the result was written, after the run
    # ("ValueError: VLEN strings do not support embedded NULLs", a traceback)
    ("title", "a\x00b", r"title: control character '\\x00' at position 1"),
    ("description", "x\x1b[31mred", r"description: control character '\\x1b' at position 1"),
    ("reference", "\x7f", r"reference: control character '\\x7f' at position 0"),
])
def test_a_scenes_text_refuses_control_characters(key, value, shown):
    with pytest.raises(InputError, match=shown):
        load_scene("wall_free", overrides=[f"{key}={json.dumps(value)}"])
    allowed = "tab\tand\nlines"
    ok = load_scene("wall_free", overrides=[f"{key}={json.dumps(allowed)}"])
    assert getattr(ok, key) == allowed


def test_a_case_table_cannot_change_the_unit_system(tmp_path):
    """A ``[cases.si]`` table with ``units = "N-m-s"`` read every kip and inch of the scene
    as newton and metre (peak u 0.3705 'm' with exit 0); ``--set units`` was already refused."""
    scene = load_scene("wall_free")
    text = open(scene.source).read() + '\n[cases.si]\nunits = "N-m-s"\n'
    path = tmp_path / "caseunits.toml"
    path.write_text(text)
    with pytest.raises(InputError, match="cases.si.units = 'N-m-s': every number of this scene "
                                         "is in 'kip-in-s'; a case table cannot convert them"):
        load_scene(str(path), case="si")


@pytest.mark.parametrize("key", ["structure..weight", ".structure.weight", "structure.weight.",
                                 "structure. .weight"])
def test_an_override_key_with_an_empty_part_is_refused(key):
    """``structure..weight=1`` was read as ``structure.weight=1``."""
    with pytest.raises(InputError, match="the key has an empty part"):
        load_scene("wall_free", overrides=[f"{key}=1"])


def test_a_record_whose_times_do_not_start_at_zero_says_it_is_shifted(tmp_path, caplog):
    """A record starting at 5 s: its first sample is upliftlab's at 0 s (a motion is samples
    at a uniform step), and that is said once, naming the file, the line and the 5 s (before:
    shifted silently). A record starting at 0 s says nothing. Reference: the file's own rows."""
    import logging

    late, zero = tmp_path / "late.txt", tmp_path / "zero.txt"
    late.write_text("# a header\n5.00 0.1\n5.02 0.2\n5.04 0.3\n")
    zero.write_text("0.00 0.1\n0.02 0.2\n0.04 0.3\n")
    with caplog.at_level(logging.WARNING, logger="upliftlab"):
        motion = read_motion(late)
        read_motion(late)
        read_motion(zero)
    said = [r.getMessage() for r in caplog.records]
    assert said == [f"upliftlab: note: motion file {str(late)!r} line 2: its times start at "
                    "5 s; the record starts at 0 s with this sample (its times shifted by -5 s)"]
    assert motion.dt == pytest.approx(0.02, rel=1e-12)
    np.testing.assert_allclose(motion.acceleration, [0.1, 0.2, 0.3], rtol=0)
