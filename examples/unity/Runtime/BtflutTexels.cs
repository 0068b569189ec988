// btflut for Unity: an export folder's files (docs/engines.md) as the texel arrays Unity's
// textures take. Plain C# (no UnityEngine), so it runs and is tested outside Unity
// (tests/unity_check.sh runs it under Mono against Python's decoder).
// Copyright the btflut authors; MIT licence.
using System;
using System.Collections.Generic;
using System.IO;
using System.IO.Compression;

namespace Btflut
{
    /// A decoded PNG: rows top first, channels interleaved; 8-bit samples 0..255, 16-bit 0..65535.
    public sealed class PngImage
    {
        public int Width, Height, Channels, Depth;
        public ushort[] Samples;
    }

    public static class BtflutTexels
    {
        static uint BigEndian(byte[] b, int at) =>
            (uint)(b[at] << 24 | b[at + 1] << 16 | b[at + 2] << 8 | b[at + 3]);

        /// A PNG of 8 or 16 bits, grey, grey-alpha, RGB or RGBA, not interlaced. Unity's own
        /// decoder (ImageConversion.LoadImage) may give 8 bits; the LUTs need all 16.
        public static PngImage DecodePng(byte[] bytes, string name)
        {
            byte[] signature = {137, 80, 78, 71, 13, 10, 26, 10};
            for (int i = 0; i < 8; ++i)
                if (bytes.Length < 8 || bytes[i] != signature[i]) throw new InvalidDataException(name + ": not a PNG file");
            var image = new PngImage();
            int type = -1;
            var data = new MemoryStream();
            for (int at = 8; at + 8 <= bytes.Length;)
            {
                int length = (int)BigEndian(bytes, at);
                string kind = System.Text.Encoding.ASCII.GetString(bytes, at + 4, 4);
                if (length < 0 || at + 12 + length > bytes.Length) throw new InvalidDataException(name + ": truncated " + kind + " chunk");
                if (kind == "IHDR")
                {
                    image.Width = (int)BigEndian(bytes, at + 8);
                    image.Height = (int)BigEndian(bytes, at + 12);
                    image.Depth = bytes[at + 16];
                    type = bytes[at + 17];
                    if (bytes[at + 20] != 0) throw new InvalidDataException(name + ": interlaced PNGs are not read");
                }
                else if (kind == "IDAT") data.Write(bytes, at + 8, length);
                else if (kind == "IEND") break;
                at += 12 + length;
            }
            var channelsOf = new Dictionary<int, int> {{0, 1}, {2, 3}, {4, 2}, {6, 4}};
            if (!channelsOf.ContainsKey(type) || (image.Depth != 8 && image.Depth != 16))
                throw new InvalidDataException(name + ": PNG colour type " + type + ", depth " + image.Depth + " not read");
            image.Channels = channelsOf[type];
            int step = image.Channels * image.Depth / 8, stride = image.Width * step;
            var raw = new byte[(long)image.Height * (stride + 1)];
            data.Position = 2;  // the zlib header; DeflateStream reads the raw deflate data after it
            using (var inflate = new DeflateStream(data, CompressionMode.Decompress))
            {
                int got = 0;
                for (int n; got < raw.Length && (n = inflate.Read(raw, got, raw.Length - got)) > 0;) got += n;
                if (got < raw.Length) throw new InvalidDataException(name + ": truncated image data");
            }
            var rows = new byte[(long)image.Height * stride];
            for (int y = 0; y < image.Height; ++y)
            {
                int filter = raw[y * (stride + 1)], line = y * (stride + 1) + 1, row = y * stride, up = row - stride;
                for (int i = 0; i < stride; ++i)
                {
                    int a = i >= step ? rows[row + i - step] : 0, b = y > 0 ? rows[up + i] : 0,
                        c = y > 0 && i >= step ? rows[up + i - step] : 0, predictor = 0;
                    if (filter == 1) predictor = a;
                    else if (filter == 2) predictor = b;
                    else if (filter == 3) predictor = (a + b) >> 1;
                    else if (filter == 4)
                    {
                        int p = a + b - c, pa = Math.Abs(p - a), pb = Math.Abs(p - b), pc = Math.Abs(p - c);
                        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
                    }
                    else if (filter != 0) throw new InvalidDataException(name + ": bad PNG filter " + filter);
                    rows[row + i] = (byte)(raw[line + i] + predictor);
                }
            }
            image.Samples = new ushort[(long)image.Width * image.Height * image.Channels];
            for (long i = 0; i < image.Samples.Length; ++i)
                image.Samples[i] = image.Depth == 16 ? (ushort)(rows[2 * i] << 8 | rows[2 * i + 1]) : rows[i];
            return image;
        }

        /// A float in [0, 1] as an IEEE half, rounded to nearest (Unity's Mathf.FloatToHalf does the same).
        public static ushort ToHalf(float value)
        {
            uint bits = BitConverter.ToUInt32(BitConverter.GetBytes(value), 0);
            int exponent = (int)((bits >> 23) & 255) - 112, mantissa = (int)(bits & 0x7fffff);
            if (exponent <= 0) return 0;  // below 2^-14: nothing the LUTs need
            return (ushort)Math.Min(0x7bff, (exponent << 10) + ((mantissa + 0x1000) >> 13));
        }

        /// luts.png as a Texture3D's texels: width `entries`, height `grid`, depth rows / grid, in
        /// the PNG's row order (x fastest, then y, then z: Unity's and GL's 3D order). One channel
        /// (RHalf) or RGB as RGBA (RGBAHalf); half floats, which every platform filters.
        public static ushort[] LutTexels(PngImage luts, int entries, int grid, out int depth, out int channels)
        {
            if (luts.Width != entries || luts.Depth != 16 || grid < 2 || luts.Height % (grid * grid) != 0)
                throw new InvalidDataException("luts.png: not the 16-bit " + entries + " x (" + grid + " x " + grid +
                                               " x blocks) image material.json describes");
            depth = luts.Height / grid;
            channels = luts.Channels == 1 ? 1 : 4;
            long texels = (long)luts.Width * luts.Height;
            var halves = new ushort[texels * channels];
            for (long i = 0; i < texels; ++i)
                for (int c = 0; c < channels; ++c)
                    halves[i * channels + c] =
                        c < luts.Channels ? ToHalf(luts.Samples[i * luts.Channels + c] / 65535f) : (ushort)0x3c00;
            return halves;
        }

        // An image as RGBA texels, rows bottom first (texture v = 0 at the image's bottom, so +v
        // is image up, the tangent frame's +y); grey in R, G and B, `opaque` where it has no alpha.
        static T[] RgbaBottomFirst<T>(PngImage image, Func<ushort, T> convert, T opaque)
        {
            var out_ = new T[(long)image.Width * image.Height * 4];
            for (int y = 0; y < image.Height; ++y)
                for (int x = 0; x < image.Width; ++x)
                {
                    long from = ((long)(image.Height - 1 - y) * image.Width + x) * image.Channels,
                         to = ((long)y * image.Width + x) * 4;
                    for (int c = 0; c < 4; ++c)
                        out_[to + c] = c < 3 ? convert(image.Samples[from + (image.Channels < 3 ? 0 : c)])
                                       : image.Channels == 2 || image.Channels == 4
                                           ? convert(image.Samples[from + image.Channels - 1]) : opaque;
                }
            return out_;
        }

        /// An 8-bit image as RGBA32 texels, rows bottom first, alpha 255 where it has none.
        public static byte[] Rgba32BottomFirst(PngImage image, string name)
        {
            if (image.Depth != 8) throw new InvalidDataException(name + ": not an 8-bit image");
            return RgbaBottomFirst(image, s => (byte)s, (byte)255);
        }

        /// A 16-bit image as RGBAHalf texels, rows bottom first, alpha 1 where it has none.
        public static ushort[] RgbaHalfBottomFirst(PngImage image) =>
            RgbaBottomFirst(image, s => ToHalf(s / 65535f), (ushort)0x3c00);

        /// weights.bin (float32 little-endian, [layer][j][i][4]) as RGBAFloat texels, layer by layer;
        /// row j is the texture's row j (the include reads it with exact texel fetches).
        public static float[] Weights(byte[] bytes, int size, int layers)
        {
            if (bytes.Length != (long)size * size * layers * 16)
                throw new InvalidDataException("weights.bin: not the " + size + "x" + size + "x" + layers +
                                               " RGBA float32 layers material.json describes");
            var out_ = new float[bytes.Length / 4];
            for (int i = 0; i < out_.Length; ++i)
            {
                if (!BitConverter.IsLittleEndian) Array.Reverse(bytes, 4 * i, 4);
                out_[i] = BitConverter.ToSingle(bytes, 4 * i);
            }
            return out_;
        }
    }
}
