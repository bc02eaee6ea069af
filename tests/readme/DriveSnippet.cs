// Runs the README's C# snippet: loads every model file given, streams a
// synthetic swaying skeleton through each, and checks that final labels come.
//   mono drive.exe BLOB...
using System;

public static class DriveSnippet
{
    public static int Main(string[] args)
    {
        if (args.Length == 0) { Console.Error.WriteLine("usage: drive.exe BLOB..."); return 2; }
        var recognisers = new ActionStringRecogniser[args.Length];
        for (int m = 0; m < args.Length; ++m) recognisers[m] = new ActionStringRecogniser(args[m]);
        var settled = new int[args.Length];
        for (int f = 0; f < 900; ++f) {
            if (f >= 400 && f < 490) continue;  // 1.5 s without frames: the stream restarts, its tail flushed
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
                string label = recognisers[m].Push(f * 16667L, xyz);
                if (label == null) continue;
                if (label.Length == 0) return 1;
                ++settled[m];
            }
        }
        int failures = 0;
        for (int m = 0; m < args.Length; ++m)
        {
            Console.WriteLine(args[m] + ": " + settled[m] + " final labels from 810 frames (a 1.5 s gap among 900)");
            if (settled[m] == 0) ++failures;
            recognisers[m].Dispose();
        }
        return failures == 0 ? 0 : 1;
    }
}
