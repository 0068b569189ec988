// tests/unity_check.sh: the Unity importer's plain-C# part (examples/unity/Runtime/BtflutTexels.cs)
// run under Mono on an export folder; writes what it decoded for Python to compare.
//   mono TexelsCheck.exe EXPORT_DIR OUT_DIR
using System;
using System.IO;
using Btflut;

static class TexelsCheck
{
    static void WriteShorts(string path, ushort[] values)
    {
        var bytes = new byte[values.Length * 2];
        Buffer.BlockCopy(values, 0, bytes, 0, bytes.Length);
        File.WriteAllBytes(path, bytes);
    }

    static int Main(string[] args)
    {
        string folder = args[0], output = args[1];
        string json = File.ReadAllText(Path.Combine(folder, "material.json"));
        // The grid size and entries, as JsonUtility would read them (no JSON library here).
        Func<string, int> field = name =>
        {
            int at = json.IndexOf("\"" + name + "\":", StringComparison.Ordinal);
            int from = at + name.Length + 3;
            while (json[from] == ' ') ++from;
            int to = from;
            while (char.IsDigit(json[to])) ++to;
            return int.Parse(json.Substring(from, to - from));
        };
        PngImage luts = BtflutTexels.DecodePng(File.ReadAllBytes(Path.Combine(folder, "luts.png")), "luts.png");
        int depth, channels;
        ushort[] halves = BtflutTexels.LutTexels(luts, field("entries"), field("grid_size"), out depth, out channels);
        WriteShorts(Path.Combine(output, "luts.u16"), luts.Samples);
        WriteShorts(Path.Combine(output, "luts.f16"), halves);
        PngImage plane = BtflutTexels.DecodePng(File.ReadAllBytes(Path.Combine(folder, "planes-0.png")), "planes-0.png");
        File.WriteAllBytes(Path.Combine(output, "planes-0.rgba"), BtflutTexels.Rgba32BottomFirst(plane, "planes-0.png"));
        Console.WriteLine(luts.Width + " " + luts.Height + " " + depth + " " + channels);
        try
        {
            BtflutTexels.DecodePng(new byte[] {1, 2, 3}, "x.png");
            return 1;
        }
        catch (InvalidDataException e)
        {
            Console.WriteLine(e.Message);
        }
        return 0;
    }
}
