"""Reproductions of the source papers' claims, run by ``soccer-env paper <name>``.

Each module simulates the paper's setting, prints the paper's figures beside ours and writes
tables (Markdown and CSV) and PNG plots to an output folder.
"""

PAPERS = {
    "ekf": "paper 002: EKF ball prediction with latency compensation (open and closed loop)",
    "ungm": "paper 000: bootstrap PF, FBPF and MFBPF on the UNGM benchmark",
    "localization": "paper 001: KLD-sampling localization against fixed-size filters, walking",
    "hough": "paper 000: Hough-space fusion of several robots' sightings (Table 1 geometry)",
    "team": "paper 000 in the closed loop: humanoid matches and keeper, one robot alone "
            "against team fusion and particle tracking",
}
