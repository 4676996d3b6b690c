"""Restitution curves of the damping factors: the restitution e_eff that each law produces in a
free impact against the input coefficient c_e (exact relation of contact-laws.md §1.3), plus
the input itself (what the "exact" factor reproduces).

Usage: python restitution_curve.py [OUTPUT.png]   (default: restitution_curve.png)
"""

import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt
import numpy as np

import clr_contact as cc


def main(path="restitution_curve.png"):
    c_e = np.linspace(0.05, 1.0, 96)
    fig, ax = plt.subplots(figsize=(7, 5))
    for name in ["hunt-crossley", "lankarani-nikravesh", "gonthier", "zhiying-qishao",
                 "flores", "hu-guo", "lee-wang"]:
        e = cc.effective_restitution(cc.damping_chi(name, c_e))
        ax.plot(c_e, e, label=name)
    ax.plot(c_e, c_e, "k--", label="e = c_e (exact)")
    # A single law, evaluated through its object: the journal-bearing "LN" preset at c_e = 0.5.
    ln = cc.NormalLaw.preset("LN", 0.5)
    ax.plot([0.5], [ln.effective_restitution], "ko")
    ax.annotate(f"LN preset at c_e = 0.5: {ln.effective_restitution:.4f}",
                xy=(0.5, ln.effective_restitution), xytext=(0.6, 0.45),
                arrowprops={"arrowstyle": "->"})
    ax.set_xlabel("input coefficient of restitution c_e")
    ax.set_ylabel("effective restitution e_eff")
    ax.set_title("Restitution produced by multiplicative damping laws")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    print(main(*sys.argv[1:]))
