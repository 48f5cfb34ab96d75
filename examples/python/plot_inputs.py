"""The paper's move of navy-planar from Python: the inputs of BDF-4 at
dt = 0.01 s, what the audit found, and a plot of u(t) if matplotlib is
installed (written to out/navy-planar-inputs.png).

    pip install ./crane-py        # from the checkout (builds the wheel)
    python examples/python/plot_inputs.py
"""

from pathlib import Path

import crane

r = crane.run("navy-planar", scheme="bdf4")
for name, peak in zip(r.inputs, abs(r.u).max(axis=0)):
    print(f"peak |{name}| = {peak:.3f} N m")
print("warnings:", r.warnings or "none")

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no plot")
else:
    fig, ax = plt.subplots()
    for k, name in enumerate(r.inputs):
        ax.plot(r.t, r.u[:, k], label=name)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("u [N m]")
    ax.legend()
    out = Path("out")
    out.mkdir(exist_ok=True)
    fig.savefig(out / "navy-planar-inputs.png", dpi=120)
    print(f"wrote {out / 'navy-planar-inputs.png'}")
