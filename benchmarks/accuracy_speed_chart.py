"""The chart of `accuracy_speed.py`: error against wall time of its three problems (PNG), and the Pareto front
of (time, error) points."""


def pareto(points):
    """Indices of the points (time, error) not dominated by another one (less time and less error)."""
    idx = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e and (t2, e2) != (t, e)) for t2, e2 in points):
            idx.append(i)
    return sorted(idx, key=lambda i: points[i][0])


def chart(hertz, catt, usd, refs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    ax = axes[0]
    styles = {"rollcontact": "o-", "tamaas": "s--", "contactmechanics": "^:"}
    tol_show = 1e-8
    for code in ("rollcontact", "tamaas", "contactmechanics"):
        pts = sorted([r for r in hertz if r["code"] == code and r["tol"] == tol_show and "time_s" in r],
                     key=lambda r: r["dx"], reverse=True)
        if pts:
            ax.loglog([r["time_s"] for r in pts], [abs(r["d_err"]) for r in pts], styles[code],
                      label=f"{code} (tol 1e-8)")
            for r in pts if code == "rollcontact" else []:
                ax.annotate(f"{r['a_over_dx']:.0f}", (r["time_s"], abs(r["d_err"])), fontsize=7)
    other = [r for r in hertz if r["code"] == "rollcontact" and r["tol"] != tol_show]
    ax.loglog([r["time_s"] for r in other], [abs(r["d_err"]) for r in other], ".", color="grey",
              label="rollcontact, other tol")
    ax.set(xlabel="solve wall time (s)", ylabel="|d/d_Hertz - 1|", title="(a) Hertz approach (labels: a/dx)")
    ax.legend(fontsize=7)
    ax = axes[1]
    for tol in sorted({r["tol"] for r in catt}):
        pts = sorted([r for r in catt if r["tol"] == tol and "time_s" in r], key=lambda r: r["dx"], reverse=True)
        ax.loglog([r["time_s"] for r in pts], [max(abs(r["U_err"]), 1e-9) for r in pts], "o-", label=f"tol {tol:.0e}")
    ax.set(xlabel="tangential solve wall time (s)", ylabel="|U/U_Mindlin - 1|",
           title="(b) Cattaneo-Mindlin f_t = 0.5 (nu = 0, beta = 0)")
    ax.legend(fontsize=7)
    ax = axes[2]
    for angle, mk in ((90, "o"), (0, "s")):
        ref = refs.get(str(angle))
        if not ref:
            continue
        pts = [r for r in usd if r["angle"] == angle and "u_end" in r]
        t = [r["time_s"] for r in pts]
        e = [max(abs(r["u_end"] / ref["reference"] - 1), 1e-7) for r in pts]
        ax.loglog(t, e, mk, label=f"{'perpendicular' if angle == 90 else 'parallel'}", alpha=0.7)
        for i in pareto(list(zip(t, e))):
            r = pts[i]
            ax.annotate(f"{r['dx']:g}/{r['dW']:g}/{r['tol']:.0e}", (t[i], e[i]), fontsize=6)
    ax.axhline(0.01, color="k", lw=0.7, ls="--")
    ax.set(xlabel="run wall time (s, 10 periods)", ylabel="|u_sd/u* - 1|",
           title="(c) u_sd, paper scene (labels: Pareto dx/dW/tol)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
