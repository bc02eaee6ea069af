// Runs the README's C# snippet: loads every model file given, streams a
// synthetic swaying skeleton through each (with a gap that restarts the
// stream), ends the stream, and checks the actions it reported: each one
// starts once and ends once with the same label, in time order, with a
// confidence in [0, 1]; none is left running after the end.
//   mono drive.exe BLOB...
using System;

public static class DriveSnippet
{
    // What the handler saw of one model's stream.
    sealed class ActionLog {
        public int Starts, Ends, Errors;
        public bool Running;
        public string Label = "";
        public double LastStartS = double.NegativeInfinity;

        public void OnAction(string label, bool started, double startS, double endS, float confidence) {
            if (string.IsNullOrEmpty(label) || !(confidence >= 0f && confidence <= 1f) || !(startS <= endS)) {
                ++Errors;
                return;
            }
            if (started) {
                if (Running || startS < LastStartS) ++Errors;  // an action starts once, in order
                ++Starts;
                Running = true;
                LastStartS = startS;
                Label = label;
            } else {
                if (!Running || label != Label || startS != LastStartS) ++Errors;
                ++Ends;
                Running = false;
            }
        }
    }

    public static int Main(string[] args)
    {
        if (args.Length == 0) { Console.Error.WriteLine("usage: drive.exe BLOB..."); return 2; }
        var recognisers = new ActionStringRecogniser[args.Length];
        var logs = new ActionLog[args.Length];
        var reported = new int[args.Length];
        for (int m = 0; m < args.Length; ++m) {
            recognisers[m] = new ActionStringRecogniser(args[m]);
            logs[m] = new ActionLog();
        }
        float[][] last = new float [args.Length][];
        for (int f = 0; f < 900; ++f) {
            if (f >= 400 && f < 490) continue;  // 1.5 s without frames: the stream restarts, its action ends
            for (int m = 0; m < args.Length; ++m)
            {
                int joints = recognisers[m].JointCount;
                var xyz = new float[3 * joints];
                for (int j = 0; j < joints; ++j)
                {
                    xyz[3 * j + 0] = 0.1f * (j % 5) - 0.2f + 0.05f * (float)Math.Sin(0.05 * f);
                    xyz[3 * j + 1] = 0.75f + 0.05f * (j % 7);
                    xyz[3 * j + 2] = 0.08f * (j % 3) + 0.01f * m;
                }
                int events = recognisers[m].Push(f * 16667L, xyz, logs[m].OnAction);
                if (events < 0) {
                    Console.Error.WriteLine(args[m] + ": frame " + f + " refused");
                    return 1;
                }
                reported[m] += events;
                last[m] = xyz;
            }
        }
        // A frame 10 ms before the last one (a reordered packet) is refused, and reports nothing.
        if (recognisers[0].Push(899 * 16667L - 10000, last[0], logs[0].OnAction) != -1) {
            Console.Error.WriteLine(args[0] + ": a frame before the last was not refused");
            return 1;
        }
        int failures = 0;
        for (int m = 0; m < args.Length; ++m)
        {
            int events = recognisers[m].Finish(logs[m].OnAction);
            if (events < 0) {
                Console.Error.WriteLine(args[m] + ": the stream could not end");
                return 1;
            }
            reported[m] += events;
            ActionLog log = logs[m];
            Console.WriteLine(args[m] + ": " + log.Starts + " actions started, " + log.Ends + " ended, " + reported[m] +
                              " events from 810 frames (a 1.5 s gap among 900)");
            if (log.Errors != 0 || log.Starts == 0 || log.Starts != log.Ends || log.Running ||
                reported[m] != log.Starts + log.Ends)
                ++failures;
            recognisers[m].Dispose();
        }
        return failures == 0 ? 0 : 1;
    }
}
