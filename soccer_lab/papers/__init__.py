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
    "meanshift": "paper 003: the feature-restricted mean-shift PF against plain PFs on robots "
                 "manoeuvring in rendered overhead images",
    "following": "paper 004: the Kalman-started mean shift against plain mean shift on a "
                 "turning humanoid's head-camera images",
}
