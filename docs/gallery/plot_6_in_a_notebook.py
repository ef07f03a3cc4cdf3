"""
In a notebook: tables, plots, progress bars and the soil picture
================================================================

Every result shows itself in Jupyter: its value is a table (kind, scene, span, the peaks with
their units, the code's digest), ``plot()`` returns a matplotlib figure of its histories
(θ, uplift, settlement and the M–θ loops by default; ``variables=`` and ``ax=`` choose), and a
continuum result's ``render(model)`` returns the soil picture at a snapshot: the deformed
mesh coloured by plastic strain, the footing, and the contact pressure and gap along its
base. A continuum run in a cell draws a progress bar (elapsed time, rate, ETA; tqdm, a widget
where ipywidgets is installed). Nothing is written to a file. Download this page as a notebook
to run it in Jupyter (``tests/test_notebook.py`` runs it so, in a kernel).
"""

# %%
# The strip footing on undrained clay, in the reduced model (a Winkler bed of 20
# compression-only springs) under its Ricker pulse. Its value in a cell is its table.
from upliftlab import load_scene
from upliftlab.reduced import run

scene = load_scene("strip_footing_clay")
winkler = run(scene)
print(f"peak θ = {winkler.peaks['theta']:.4g} rad")
winkler

# %%
# ``plot()`` returns the figure; the lines are the result's own arrays.
fig = winkler.plot()
reduced_theta_plotted = fig.axes[0].lines[0].get_ydata()
fig

# %%
# The same scene on a coarse plane-strain continuum (4 Q2 elements across the footing), for the
# first second of the pulse: the cell shows a progress bar while it runs.
from upliftlab.continuum import DynamicOptions, build_model, run_dynamic

coarse = load_scene("strip_footing_clay", overrides=["continuum.elements_across=4",
                                                     "motion.duration=1.0"])
model = build_model(coarse)
continuum = run_dynamic(model, coarse, coarse.build_motion(), DynamicOptions(snapshots=3))
print(f"peak |θ| = {abs(continuum.theta).max():.4g} rad")
continuum

# %%
# Its histories, and the soil at the snapshot of largest rotation.
continuum.plot()

# %%
picture = continuum.render(model)
picture
