"""The AR cues' colours (RGB, 0-255), as the original system drew them: a red beam, a green
distance bar and target, a blue grip bar; the ghost is a translucent grey so it never reads as
one of the cues, and the predictive ghost a translucent amber, told apart from it (RGBA, 0-1).
A cue without an estimate (the distance bar while the bowl is not tracked) turns grey. The depth
aids, no AR cue, are magenta."""

BEAM_RGB = (255, 0, 0)
DISTANCE_RGB = (0, 200, 0)
GRIP_RGB = (0, 60, 255)
TARGET_RGB = (0, 200, 0)
GHOST_RGBA = (0.85, 0.85, 0.9, 0.45)
PREDICTIVE_RGBA = (1.0, 0.6, 0.0, 0.45)
NO_ESTIMATE_RGB = (128, 128, 128)
AIDS_RGB = (255, 0, 255)
"""The depth aids are magenta: no cue's colour, and seen on the grey table and on the black marks
drawn on it alike. They were near-black until a pointing study's ring, lined up with its black
start cross and target circle, vanished among their lines (the scripted pointer in a browser
lost it there)."""
