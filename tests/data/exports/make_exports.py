#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Write the logger and app exports of tests/data/exports (Python 3 stdlib).

Every file is made up here, in the shape a logger or an app writes (its
header, its units, its time format, its delimiter and decimal mark, its
preamble, its line ends); none is a copy of third-party data.  The signal
is the same in all of them: a truck bed at rest, then a braking half-sine
of 0.25 g over 0.5 s, with a little road noise (fixed seed), gravity on
the vertical axis.  The crate of sample_logs/crate.ini does not rock on it
(it needs 0.364 g), so each file's verdict is upright and its exit code 0
once it is read right.  README.md says what each file imitates.

    python3 tests/data/exports/make_exports.py [OUTDIR]
"""
import math
import os
import random
import sys

G0 = 9.80665  # m/s^2 per g
T0 = 1716206400  # s since 1970: 2024-05-20T12:00:00Z (date -u -d 2024-05-20T12:00:00Z +%s)


def signal(rate, seconds, seed):
    """[(t, ax, ay, az)] in s and g: rest, a braking pulse at 1 s, rest."""
    rnd = random.Random(seed)
    out = []
    for i in range(int(round(rate * seconds))):
        t = i / rate
        ax = -0.25 * math.sin(math.pi * (t - 1.0) / 0.5) if 1.0 <= t <= 1.5 else 0.0
        out.append((t, ax + rnd.gauss(0, 0.004), rnd.gauss(0, 0.004), 1.0 + rnd.gauss(0, 0.004)))
    return out


def write(path, text, crlf=False, bom=False):
    data = text.replace("\n", "\r\n") if crlf else text
    with open(path, "wb") as f:
        if bom:
            f.write(b"\xef\xbb\xbf")
        f.write(data.encode("utf-8"))


def comma(s):
    """A number written with a decimal comma."""
    return s.replace(".", ",")


def iso(t, sep=" ", frac=3):
    """t s after T0 as 2024-05-20 12:00:00.000 (UTC)."""
    whole = int(math.floor(t + 1e-9))
    ms = int(round((t - whole) * 10**frac))
    s = T0 + whole
    h, m, sec = (s // 3600) % 24, (s // 60) % 60, s % 60
    out = "2024-05-20%s%02d:%02d:%02d" % (sep, h, m, sec)
    return out + (".%0*d" % (frac, ms) if frac else "")


def clock(t, frac=3):
    """The time of day of t s after T0: 12:00:00.000."""
    return iso(t, frac=frac).split(" ")[1]


def files(out):
    made = {}

    # A shock recorder's export: lines about the recording, then the table.
    sig = signal(200, 3, 1)
    lines = [
        "Shock & Vibration Recorder Export",
        "Instrument:,SR-3X90",
        "Serial Number:,10427",
        "Event:,17",
        "Trigger:,X axis level 0.20 G",
        "Sample Rate:,200 Hz",
        "Pre-trigger:,33 %",
        "Units:,G",
        "Time (sec),X Axis (G),Y Axis (G),Z Axis (G)",
    ]
    lines += ["%.3f,%.4f,%.4f,%.4f" % r for r in sig]
    made["saver-preamble.csv"] = ("\n".join(lines) + "\n", {})

    # A 3-axis data logger's export: channels named by axis and range.
    sig = signal(500, 2.5, 2)
    lines = ['"Time (s)","X (100g)","Y (100g)","Z (100g)","Temperature (\u00b0C)"']
    lines += ["%.6f,%.5f,%.5f,%.5f,21.4" % r for r in sig]
    made["endaq-3axis.csv"] = ("\n".join(lines) + "\n", {})

    # An iPhone logging app: every name carries its unit in brackets; a GPS
    # clock once a second, the accelerometer's own clock, a text time.
    sig = signal(100, 3, 3)
    lines = [
        "loggingTime(txt),loggingSample(N),locationTimestamp_since1970(s),"
        "locationLatitude(WGS84),locationLongitude(WGS84),locationSpeed(m/s),"
        "accelerometerTimestamp_sinceReboot(s),accelerometerAccelerationX(G),"
        "accelerometerAccelerationY(G),accelerometerAccelerationZ(G)"
    ]
    for i, (t, ax, ay, az) in enumerate(sig):
        lines.append(
            "%s,%d,%.3f,48.137154,11.576124,13.90,%.6f,%.5f,%.5f,%.5f"
            % (iso(t), i, T0 + math.floor(t), 81234.5 + t, ax, ay, -az)
        )
    made["sensorlog-iphone.csv"] = ("\n".join(lines) + "\n", {})

    # The same app's older export: the same names without their units.
    lines = [
        "loggingTime,loggingSample,accelerometerTimestamp_sinceReboot,"
        "accelerometerAccelerationX,accelerometerAccelerationY,accelerometerAccelerationZ"
    ]
    for i, (t, ax, ay, az) in enumerate(sig):
        lines.append("%s,%d,%.6f,%.5f,%.5f,%.5f" % (iso(t), i, 81234.5 + t, ax, ay, -az))
    made["sensorlog-nounits.csv"] = ("\n".join(lines) + "\n", {})

    # A phone sensor app: epoch ns and seconds elapsed, axes in m/s^2
    # (z, y, x in that order), as its Accelerometer.csv.
    sig = signal(100, 3, 4)
    lines = ["time,seconds_elapsed,z,y,x"]
    for t, ax, ay, az in sig:
        ns = T0 * 10**9 + int(round(t * 1e9))
        lines.append("%d,%.6f,%.5f,%.5f,%.5f" % (ns, t, az * G0, ay * G0, ax * G0))
    made["sensor-logger.csv"] = ("\n".join(lines) + "\n", {})

    # A physics app: quoted names, units in brackets, scientific notation.
    sig = signal(100, 3, 5)
    lines = [
        '"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)",'
        '"Acceleration z (m/s^2)","Absolute acceleration (m/s^2)"'
    ]
    for t, ax, ay, az in sig:
        a = [ax * G0, ay * G0, az * G0]
        lines.append(",".join("%.9E" % v for v in [t] + a + [math.sqrt(sum(v * v for v in a))]))
    made["phyphox.csv"] = ("\n".join(lines) + "\n", {})

    # A sensor toolbox app's g-force meter: gFx, gFy, gFz in g, TgF the total.
    sig = signal(100, 3, 6)
    lines = ["time,gFx,gFy,gFz,TgF"]
    for t, ax, ay, az in sig:
        tot = math.sqrt(ax * ax + ay * ay + az * az)
        lines.append("%.3f,%.4f,%.4f,%.4f,%.4f" % (t, ax, ay, az, tot))
    made["physics-toolbox.csv"] = ("\n".join(lines) + "\n", {})

    # An Android logging app: the uptime clock in ns, axes in m/s^2.
    sig = signal(100, 3, 7)
    lines = ["uptimeNanos,x,y,z"]
    for t, ax, ay, az in sig:
        ns = 36000 * 10**9 + int(round(t * 1e9))
        lines.append("%d,%.5f,%.5f,%.5f" % (ns, ax * G0, ay * G0, az * G0))
    made["android-uptime-nanos.csv"] = ("\n".join(lines) + "\n", {})

    # A vehicle data logger (CAN and GPS channels): the GPS position names
    # the x axis, in degrees; the acceleration is "Acceleration Gs".
    sig = signal(50, 4, 8)
    lines = [
        "Time (s),Latitude / Y Position (Degrees),Longitude / X Position (Degrees),"
        "Speed (km/h),Heading (Degrees),Acceleration Gs,Lateral Gs,Engine Speed (rpm)"
    ]
    for t, ax, ay, az in sig:
        v = 50.0 - (9.80665 * 0.25 * 0.5 * 2 / math.pi * 3.6 if t > 1.5 else 0.0)
        lines.append(
            "%.2f,%.7f,%.7f,%.1f,87.5,%.3f,%.3f,%d"
            % (t, 48.137154 + t * 1e-5, 11.576124 + t * 1.9e-4, v, ax, ay, 1850)
        )
    made["can-gps.csv"] = ("\n".join(lines) + "\n", {})

    # German and French spreadsheets: ';', decimal commas, units in brackets.
    sig = signal(100, 3, 9)
    lines = ["Zeit [s];Beschl. [m/s\u00b2]"]
    lines += [comma("%.2f;%.4f" % (t, ax * G0)) for t, ax, ay, az in sig]
    made["german-brackets.csv"] = ("\n".join(lines) + "\n", {})
    sig = signal(100, 3, 10)
    acc = "Acc\u00e9l\u00e9ration"
    lines = ["Temps (s);%s X (g);%s Y (g);%s Z (g)" % (acc, acc, acc)]
    lines += [comma("%.2f;%.4f;%.4f;%.4f" % r) for r in sig]
    made["french-parens.csv"] = ("\n".join(lines) + "\n", {})
    sig = signal(200, 2.5, 11)
    lines = ["Zeit [ms];Beschleunigung X [g];Beschleunigung Y [g];Beschleunigung Z [g]"]
    lines += [comma("%d;%.4f;%.4f;%.4f" % (round(t * 1000), ax, ay, az)) for t, ax, ay, az in sig]
    made["decimal-comma.csv"] = ("\n".join(lines) + "\n", {})

    # A Windows logger: byte-order mark, CRLF, quoted names, a sample index
    # first, time in ms.
    sig = signal(250, 2.4, 12)
    lines = ['"Sample","Time (ms)","X (g)","Y (g)","Z (g)","Temp (C)"']
    for i, (t, ax, ay, az) in enumerate(sig):
        lines.append("%d,%.0f,%.4f,%.4f,%.4f,21.5" % (i + 1, t * 1000, ax, ay, az))
    made["bom-crlf.csv"] = ("\n".join(lines) + "\n", {"crlf": True, "bom": True})

    # Date-times with the day first: '/' (a day above 12 in every row),
    # '.' in a ';' export with decimal commas, and a date whose day is not
    # above 12 (undecidable: 5 June or May 6?).
    sig = signal(100, 3, 13)
    lines = ["Date/Time,Acceleration X (g),Acceleration Y (g),Acceleration Z (g)"]
    lines += ["14/05/2016 %s,%.4f,%.4f,%.4f" % (clock(t), ax, ay, az) for t, ax, ay, az in sig]
    made["dayfirst-slash.csv"] = ("\n".join(lines) + "\n", {})
    sig = signal(100, 3, 14)
    lines = ["Datum/Uhrzeit;Beschleunigung X [g];Beschleunigung Y [g];Beschleunigung Z [g]"]
    for t, ax, ay, az in sig:
        lines.append("20.05.2024 %s;%s" % (clock(t), comma("%.4f;%.4f;%.4f" % (ax, ay, az))))
    made["dayfirst-dot.csv"] = ("\n".join(lines) + "\n", {})
    sig = signal(100, 3, 15)
    lines = ["Date,Accel X (g),Accel Y (g),Accel Z (g)"]
    lines += ["05/06/2024 %s,%.4f,%.4f,%.4f" % (clock(t), ax, ay, az) for t, ax, ay, az in sig]
    made["dayfirst-undecidable.csv"] = ("\n".join(lines) + "\n", {})

    # A US spreadsheet: month first, no leading zeros, a 12-hour clock.
    sig = signal(100, 3, 16)
    lines = ["Time,Accel X (g),Accel Y (g),Accel Z (g)"]
    for t, ax, ay, az in sig:
        hms = clock(t)
        h = int(hms[:2])
        h12 = h - 12 if h > 12 else h
        lines.append("5/14/2016 %d%s PM,%.4f,%.4f,%.4f" % (h12, hms[2:], ax, ay, az))
    made["monthfirst-ampm.csv"] = ("\n".join(lines) + "\n", {})

    # Epoch times: a "timestamp" in ms, a "time" in ns, neither with a unit.
    sig = signal(100, 3, 17)
    lines = ["timestamp,accel_x,accel_y,accel_z"]
    for t, ax, ay, az in sig:
        ms = T0 * 1000 + round(t * 1000)
        lines.append("%d,%.5f,%.5f,%.5f" % (ms, ax * G0, ay * G0, az * G0))
    made["epoch-ms.csv"] = ("\n".join(lines) + "\n", {})
    sig = signal(100, 3, 18)
    lines = ["time,x,y,z"]
    for t, ax, ay, az in sig:
        ns = (T0 * 1000 + round(t * 1000)) * 10**6
        lines.append("%d,%.5f,%.5f,%.5f" % (ns, ax * G0, ay * G0, az * G0))
    made["epoch-ns.csv"] = ("\n".join(lines) + "\n", {})

    # A date to the second beside the uptime clock in ns: the finer is time.
    sig = signal(100, 3, 19)
    lines = ["date,uptimeNanos,x,y,z"]
    for t, ax, ay, az in sig:
        lines.append(
            "%s,%d,%.5f,%.5f,%.5f"
            % (iso(t, frac=0), 36000 * 10**9 + int(round(t * 1e9)), ax * G0, ay * G0, az * G0)
        )
    made["date-1s-uptime-ns.csv"] = ("\n".join(lines) + "\n", {})

    # A logger that writes no header: time in s, the acceleration in m/s^2.
    sig = signal(100, 3, 20)
    lines = ["%.2f,%.5f" % (t, ax * G0) for t, ax, ay, az in sig]
    made["no-header.csv"] = ("\n".join(lines) + "\n", {})

    for name, (text, how) in made.items():
        write(os.path.join(out, name), text, **how)
    return sorted(made)


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name in files(out):
        print(name)
