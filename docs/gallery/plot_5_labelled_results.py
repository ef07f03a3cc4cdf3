"""
Reading a result with xarray and pandas
=======================================

Every run is labelled data: ``Response.to_xarray()`` gives an :class:`xarray.Dataset` with
time, DOF, spring, energy component and story coordinates, units on every variable, and the
run's provenance as attributes; it is also what ``upliftlab run`` writes as NetCDF.
``to_dataframe()`` gives the scalar histories as a table.
"""

# %%
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import xarray as xr

from upliftlab import load_scene
from upliftlab.reduced import run

response = run(load_scene("wall_free", case="e07"))
ds = response.to_xarray()
print(ds.spring_force.attrs.get("units"), ds.sizes)

# %%
# The energy account closes: what the structure held at the start plus what the motion put in
# (nothing, in free vibration) is what it holds at the end plus what its dashpots, impacts and
# plastic flow took.
energy = ds.energy
others = energy.sel(component=["kinetic", "strain", "gravity", "viscous", "impact", "plastic"])
residual = others.sum("component") - energy.sel(component="input")
initial = float(residual.isel(time=0))
balance_error = float(abs(residual - initial).max()) / max(
    float(abs(energy.sel(component="input")).max()), initial)
print(f"energy balance: {balance_error:.1e} of the energy in play "
      f"(the run's own check: {response.energy_balance_error:.1e})")

# %%
# One spring's force, and the scalar histories as a pandas table.
frame = response.to_dataframe()
print(frame[["u", "theta"]].describe().loc[["max", "min"]])
fig, ax = plt.subplots(figsize=(6.5, 3))
ds.spring_force.sel(spring=0).plot(ax=ax)
fig.tight_layout()

# %%
# Written to NetCDF and read back, the labels are the same.
with tempfile.TemporaryDirectory() as folder:
    path = Path(folder) / "wall.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    with xr.open_dataset(path, engine="h5netcdf") as back:
        round_trip_error = float(abs(back.u - ds.u).max())
print(f"round trip through NetCDF: largest change in u {round_trip_error:g} in")
