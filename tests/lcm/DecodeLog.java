/* SPDX-License-Identifier: GPL-3.0-or-later */
// DecodeLog.java - reads an lcm-logger file with LCM's Java API and the
// generated swaywatch types (the jar lcm-spy is given), prints the number of
// accel_t messages.  Run as a single-file program:
//   java -cp lcm.jar:swaywatch_lcmtypes.jar DecodeLog.java LOG
import java.io.EOFException;
import lcm.logging.Log;
import swaywatch.accel_t;

public class DecodeLog {
    public static void main(String[] args) throws Exception {
        Log log = new Log(args[0], "r");
        long n = 0;
        try {
            while (true) {
                Log.Event ev = log.readNext();
                if (!ev.channel.equals("ACCEL")) continue;
                accel_t m = new accel_t(ev.data);
                if (m.seq != n) throw new RuntimeException("seq " + m.seq + " != " + n);
                n++;
            }
        } catch (EOFException end) {
            // end of the log
        }
        System.out.println("decoded " + n + " accel_t");
    }
}
