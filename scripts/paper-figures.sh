#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerate the figures (docs/img) and the data (docs/data) of
# docs/paper-reproduction.md; each command is the one quoted there.
# SW names the swaywatch binary (default build/swaywatch).  Takes about half
# an hour on two cores: the scan step is 0.5 % (--step 0.005), because the
# overturning windows of a lightly damped frame under full-sine pulses can
# be narrower than the default 2 % and a coarser scan steps over them.
set -eu
cd "$(dirname "$0")/.."
SW=${SW:-build/swaywatch}
S=docs/scenes
D=docs/data
I=docs/img
R=0.5:15:0.25
STEP=0.005

# Fig. 5: frame (gamma 0.8, zeta_b 0.1) at omega_b/omega_e = 1, 1/2, 1/3 and the bare package
for pulse in half-sine full-sine; do
    f=fig5-$pulse
    "$SW" boundary --scene $S/paper-bare.ini --scene $S/paper-frame.ini --bearing-ratio 1,1/2,1/3 \
        --pulse $pulse --omega-ratio $R --max-amplitude 40 --step $STEP \
        --out $D/$f.csv --detail $D/$f-detail.csv --plot $I/$f.png \
        --title "Fig. 5 ($pulse): package on the bed and on the frame, gamma 0.8, zeta_b 0.1"
done

# Fig. 6: gamma = m/(m + m_b) = 0.2, 0.5, 0.8, 0.9 at omega_b/omega_e = 1/2
for pulse in half-sine full-sine; do
    f=fig6-$pulse
    "$SW" boundary --scene $S/paper-bare.ini --scene $S/paper-frame.ini --bearing-ratio 1/2 \
        --vary frame.mass=4000,1000,250,111.111 \
        --pulse $pulse --omega-ratio $R --max-amplitude 40 --step $STEP \
        --out $D/$f.csv --plot $I/$f.png \
        --title "Fig. 6 ($pulse): frame mass m_b 4000, 1000, 250, 111 kg (gamma 0.2, 0.5, 0.8, 0.9), omega_b/omega_e 1/2"
done

# Fig. 7: zeta_b = 0.05, 0.1, 0.2, 0.4 at omega_b/omega_e = 1/2
for pulse in half-sine full-sine; do
    f=fig7-$pulse
    "$SW" boundary --scene $S/paper-bare.ini --scene $S/paper-frame.ini --bearing-ratio 1/2 \
        --vary frame.zeta=0.05,0.1,0.2,0.4 \
        --pulse $pulse --omega-ratio $R --max-amplitude 40 --step $STEP \
        --out $D/$f.csv --plot $I/$f.png \
        --title "Fig. 7 ($pulse): bearing damping zeta_b 0.05, 0.1, 0.2, 0.4, omega_b/omega_e 1/2, gamma 0.8"
done

# Fig. 8: cushion on the frame, omega_c = 10, 20, 40, 80 p (zeta_c 0.1), and Fig. 9:
# zeta_c = 0.05, 0.1, 0.2, 0.4 (omega_c 20 p); with the bare package and the frame
# without a cushion for reference; omega_b/omega_e = 1/2.  A coarser omega grid:
# each cushion run costs more.
RC=0.5:15:0.5
for pulse in half-sine full-sine; do
    f=fig8-$pulse
    "$SW" boundary --scene $S/paper-bare.ini --scene $S/paper-frame.ini --scene $S/paper-cushion.ini \
        --bearing-ratio 1/2 --vary cushion.omega=27.12,54.25,108.5,217 \
        --pulse $pulse --omega-ratio $RC --max-amplitude 40 --step $STEP \
        --out $D/$f.csv --detail $D/$f-detail.csv --plot $I/$f.png \
        --title "Fig. 8 ($pulse): cushion on the frame, omega_c 27, 54, 108, 217 rad/s (10-80 p), zeta_c 0.1, omega_b/omega_e 1/2"
    f=fig9-$pulse
    "$SW" boundary --scene $S/paper-bare.ini --scene $S/paper-frame.ini --scene $S/paper-cushion.ini \
        --bearing-ratio 1/2 --vary cushion.zeta=0.05,0.1,0.2,0.4 \
        --pulse $pulse --omega-ratio $RC --max-amplitude 40 --step $STEP \
        --out $D/$f.csv --plot $I/$f.png \
        --title "Fig. 9 ($pulse): cushion damping zeta_c 0.05, 0.1, 0.2, 0.4, omega_c 54 rad/s (20 p), omega_b/omega_e 1/2"
done

# Frame / bare: the ratio of the boundaries of Fig. 5 (> 1: the frame helps)
for pulse in half-sine full-sine; do
    gnuplot -e "set terminal pngcairo size 900,600 enhanced font 'sans,11'; \
        set output '$I/fig5-$pulse-ratio.png'; set datafile separator ','; \
        set key autotitle columnheader top right box opaque; set grid; set logscale y; \
        set yrange [0.25:4]; set ytics (0.25, 0.5, 0.75, 1, 1.5, 2, 3, 4); set xlabel 'ω_e / p'; set ylabel 'boundary on the frame / on the bed'; \
        set title 'Fig. 5 ($pulse): does the frame help? (> 1: yes)'; \
        plot for [c=3:5] '$D/fig5-$pulse.csv' using 1:(column(c)/column(2)) with linespoints \
        pt 7 ps 0.6 lw 2 lc (c-1), 1 with lines lc rgb 'black' dt 2 notitle"
done

# The bare block of the reference tables (alpha = 0.25 rad), with the safe
# islands above the lowest overturning amplitude
for pulse in half-sine full-sine; do
    f=block025-$pulse
    "$SW" boundary --scene $S/block-alpha025.ini --pulse $pulse --omega-ratio 0.5:12:0.25 \
        --max-amplitude 30 --step $STEP --out $D/$f.csv --detail $D/$f-detail.csv --islands $D/$f-islands.csv \
        --plot $I/$f.png \
        --title "Block with alpha = 0.25 rad on the bed, $pulse pulse: lowest overturning amplitude and safe islands above it"
done
