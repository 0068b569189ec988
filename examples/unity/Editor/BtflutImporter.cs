// btflut for Unity: Assets > btflut > Import Export Folder... turns `btflut export M.btflut -o
// DIR/` into assets: the Texture3D of luts.png (the editor script docs/engines.md says is
// needed), the reference, the predictor's Texture2DArrays (planes and albedo; weights.bin) and
// labels, and a btflut/Relit material with material.json's values. Add BtflutLight to the
// object that wears it. Copyright the btflut authors; MIT licence.
using System;
using System.IO;
using UnityEditor;
using UnityEngine;

namespace Btflut
{
    // material.json, the fields the shader needs (docs/engines.md); JsonUtility fills them.
    [Serializable] public class LutsJson { public string file; public int entries, grid_size, layers, regions; }
    [Serializable] public class ReferenceJson { public string file; public int width, height, channels, bit_depth; }
    [Serializable] public class FileJson { public string file, use; public int grid_size, layers; }
    [Serializable] public class NetworkJson { public string glsl, hlsl, godot; }
    [Serializable] public class PredictorJson
    {
        public string kind;
        public int kind_index, basis_index, order, planes, channels, regions, output_channels;
        public float codes;
        public float[] scale, bias;
        public string[] images;
        public FileJson albedo, weights, labels;  // absent or null: file is empty
        public NetworkJson network;               // a learned material's decoder specialised to it; absent: hlsl is empty
    }
    [Serializable] public class MaterialJson
    {
        public string format, kind, colour;
        public int version;
        public float lut_input_code, lut_output_code;
        public LutsJson luts;
        public ReferenceJson reference;
        public PredictorJson predictor;
    }

    public static class BtflutImporter
    {
        [MenuItem("Assets/btflut/Import Export Folder...")]
        static void ImportMenu()
        {
            string folder = EditorUtility.OpenFolderPanel("A btflut export (btflut export M.btflut -o DIR/)", "", "");
            if (string.IsNullOrEmpty(folder)) return;
            Material material = Import(folder, "Assets/btflut/" + Path.GetFileName(folder.TrimEnd('/', '\\')));
            Selection.activeObject = material;
        }

        /// Makes the assets of the export in `folder` under `assetFolder` and returns the material.
        public static Material Import(string folder, string assetFolder)
        {
            var json = JsonUtility.FromJson<MaterialJson>(File.ReadAllText(Path.Combine(folder, "material.json")));
            if (json == null || json.format != "btflut-material")
                throw new InvalidDataException(folder + "/material.json: not a btflut material");
            if (json.version > 2)
                throw new InvalidDataException(folder + "/material.json: version " + json.version + " is newer than this importer reads (2)");
            Shader shader = Shader.Find("btflut/Relit");
            if (shader == null) throw new InvalidOperationException("btflut/Relit: put BtflutRelit.shader in the project");
            CopyInclude(folder, shader);
            Directory.CreateDirectory(assetFolder);
            if (json.predictor != null && json.predictor.network != null && !string.IsNullOrEmpty(json.predictor.network.hlsl))
                shader = LearnedShader(folder, shader, json.predictor.network.hlsl, assetFolder);
            Func<string, PngImage> png = file => BtflutTexels.DecodePng(File.ReadAllBytes(Path.Combine(folder, file)), file);

            var material = new Material(shader);
            int depth, channels;
            ushort[] lut = BtflutTexels.LutTexels(png(json.luts.file), json.luts.entries, json.luts.grid_size, out depth, out channels);
            var luts = new Texture3D(json.luts.entries, json.luts.grid_size, depth,
                                     channels == 1 ? TextureFormat.RHalf : TextureFormat.RGBAHalf, false)
            {
                filterMode = FilterMode.Bilinear, wrapMode = TextureWrapMode.Clamp, name = "luts"
            };
            luts.SetPixelData(lut, 0);
            luts.Apply(false, true);
            Save(luts, assetFolder, "luts.asset");
            material.SetTexture("_Luts", luts);

            bool rgbLuts = json.colour == "rgb";
            material.SetFloat("_RgbLuts", rgbLuts ? 1 : 0);
            material.SetFloat("_InputCode", json.lut_input_code);
            material.SetFloat("_OutputCode", json.lut_output_code);
            material.SetFloat("_GreyReference", json.reference.channels == 1 ? 1 : 0);
            if (json.kind == "luts")
            {
                material.SetInt("_Kind", 0);
                material.SetTexture("_Reference", Save(Texture2DOf(png(json.reference.file), "reference"), assetFolder, "reference.asset"));
                return SaveMaterial(material, assetFolder);
            }
            PredictorJson p = json.predictor;
            var files = new System.Collections.Generic.List<string>(p.images);
            if (p.albedo != null && !string.IsNullOrEmpty(p.albedo.file)) files.Add(p.albedo.file);
            PngImage first = png(files[0]);
            var planes = new Texture2DArray(first.Width, first.Height, files.Count, TextureFormat.RGBA32, true, true)
            {
                filterMode = FilterMode.Trilinear, wrapMode = TextureWrapMode.Repeat, name = "planes"
            };
            for (int k = 0; k < files.Count; ++k)
            {
                PngImage image = k == 0 ? first : png(files[k]);
                if (image.Width != first.Width || image.Height != first.Height)
                    throw new InvalidDataException(files[k] + ": not the size of " + files[0]);
                planes.SetPixelData(BtflutTexels.Rgba32BottomFirst(image, files[k]), 0, k);
            }
            planes.Apply(true, true);  // mipmaps: the prediction is linear in the planes
            material.SetTexture("_Planes", Save(planes, assetFolder, "planes.asset"));

            var weights = new Texture2DArray(1, 1, 1, TextureFormat.RGBAFloat, false, true) { name = "weights" };
            if (p.weights != null && !string.IsNullOrEmpty(p.weights.file))
            {
                weights = new Texture2DArray(p.weights.grid_size, p.weights.grid_size, p.weights.layers,
                                             TextureFormat.RGBAFloat, false, true) { name = "weights" };
                float[] texels = BtflutTexels.Weights(File.ReadAllBytes(Path.Combine(folder, p.weights.file)),
                                                      p.weights.grid_size, p.weights.layers);
                int layer = p.weights.grid_size * p.weights.grid_size * 4;
                for (int k = 0; k < p.weights.layers; ++k)
                    weights.SetPixelData(texels, 0, k, k * layer);
            }
            weights.filterMode = FilterMode.Point;
            weights.Apply(false, true);
            material.SetTexture("_Weights", Save(weights, assetFolder, "weights.asset"));
            if (p.labels != null && !string.IsNullOrEmpty(p.labels.file))
            {
                Texture2D labels = Texture2DOf(png(p.labels.file), "labels");
                labels.filterMode = FilterMode.Point;
                material.SetTexture("_Labels", Save(labels, assetFolder, "labels.asset"));
            }
            material.SetInt("_Kind", p.kind_index);  // BTFLUT_KIND_MODEL, _REFERENCES, _LEARNED
            material.SetInt("_Basis", p.kind == "model" ? p.basis_index : 0);
            material.SetInt("_Order", p.order);
            material.SetInt("_PlaneCount", p.planes);
            material.SetInt("_Channels", p.channels);
            material.SetInt("_Albedo", p.albedo == null || string.IsNullOrEmpty(p.albedo.file) ? 0 : p.albedo.use == "multiplies" ? 1 : 2);
            material.SetInt("_Regions", Math.Max(1, p.regions));
            material.SetFloat("_Codes", p.codes);
            material.SetFloat("_GreyOutput", p.output_channels == 1 ? 1 : 0);
            var scale = new float[32];
            var bias = new float[32];
            for (int k = 0; p.scale != null && k < Math.Min(32, p.scale.Length); ++k) { scale[k] = p.scale[k]; bias[k] = p.bias[k]; }
            material.SetFloatArray("_Scale", scale);
            material.SetFloatArray("_Bias", bias);
            return SaveMaterial(material, assetFolder);
        }

        // An 8-bit image as RGBA32 (a 16-bit one as RGBAHalf), rows bottom first, not sRGB: the
        // LUTs act on the stored codes.
        static Texture2D Texture2DOf(PngImage image, string name)
        {
            bool wide = image.Depth == 16;
            var texture = new Texture2D(image.Width, image.Height, wide ? TextureFormat.RGBAHalf : TextureFormat.RGBA32, false, true)
            {
                name = name, wrapMode = TextureWrapMode.Repeat
            };
            if (wide) texture.SetPixelData(BtflutTexels.RgbaHalfBottomFirst(image), 0);
            else texture.SetPixelData(BtflutTexels.Rgba32BottomFirst(image, name), 0);
            texture.Apply(false, true);
            return texture;
        }

        // btflut.hlsl beside the shader, where its #include finds it.
        static void CopyInclude(string folder, Shader shader)
        {
            string shaderFolder = Path.GetDirectoryName(AssetDatabase.GetAssetPath(shader));
            string target = Path.Combine(shaderFolder, "btflut.hlsl");
            if (File.Exists(target) && File.ReadAllText(target) == File.ReadAllText(Path.Combine(folder, "btflut.hlsl"))) return;
            File.Copy(Path.Combine(folder, "btflut.hlsl"), target, true);
            AssetDatabase.ImportAsset(target);
        }

        // A learned material's own shader: btflut/Relit with the material's decoder specialised to it
        // (btflut_network.hlsl beside it, in the asset folder) included at its "btflut: network" line.
        static Shader LearnedShader(string folder, Shader template, string network, string assetFolder)
        {
            string templatePath = AssetDatabase.GetAssetPath(template);
            string include = Path.GetDirectoryName(templatePath).Replace('\\', '/') + "/btflut.hlsl";
            File.Copy(Path.Combine(folder, network), Path.Combine(assetFolder, "btflut_network.hlsl"), true);
            string name = Path.GetFileName(assetFolder);
            string text = File.ReadAllText(templatePath)
                .Replace("Shader \"btflut/Relit\"", "Shader \"btflut/Relit " + name + "\"")
                .Replace("#include \"btflut.hlsl\"", "#include \"" + include + "\"")
                .Replace("// btflut: network", "#include \"btflut_network.hlsl\"");
            string path = assetFolder + "/relit.shader";
            File.WriteAllText(path, text);
            AssetDatabase.ImportAsset(assetFolder + "/btflut_network.hlsl");
            AssetDatabase.ImportAsset(path);
            return AssetDatabase.LoadAssetAtPath<Shader>(path);
        }

        static T Save<T>(T asset, string folder, string name) where T : UnityEngine.Object
        {
            AssetDatabase.CreateAsset(asset, folder + "/" + name);
            return asset;
        }

        static Material SaveMaterial(Material material, string folder)
        {
            Save(material, folder, "material.mat");
            AssetDatabase.SaveAssets();
            return material;
        }
    }
}
