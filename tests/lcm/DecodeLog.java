/* SPDX-License-Identifier: GPL-3.0-or-later */
// DecodeLog.java - reads an lcm-logger file with LCM's Java API and the
// generated swaywatch types (the jar lcm-spy is given), prints the number of
// accel samples: accel_v1_t (a sender without a key), or accel_t with
// "signed".  Run as a single-file program:
//   java -cp lcm.jar:swaywatch_lcmtypes.jar DecodeLog.java LOG [signed]
import java.io.EOFException;
import lcm.logging.Log;
import swaywatch.accel_t;
import swaywatch.accel_v1_t;

public class DecodeLog {
    public static void main(String[] args) throws Exception {
        Log log = new Log(args[0], "r");
        boolean signed = args.length > 1 && args[1].equals("signed");
        long n = 0;
        try {
            while (true) {
                Log.Event ev = log.readNext();
                if (!ev.channel.equals("ACCEL")) continue;
                long seq;
                if (signed) {
                    accel_t m = new accel_t(ev.data);
                    if (m.key_id == 0) throw new RuntimeException("no key id");
                    seq = m.seq;
                } else {
                    seq = new accel_v1_t(ev.data).seq;
                }
                if (seq != n) throw new RuntimeException("seq " + seq + " != " + n);
                n++;
            }
        } catch (EOFException end) {
            // end of the log
        }
        System.out.println("decoded " + n + (signed ? " accel_t" : " accel_v1_t"));
    }
}
