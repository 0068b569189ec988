# btflut for Godot 4: loads an export folder (btflut export M.btflut -o DIR/) into the
# btflut_relit.gdshader material of the MeshInstance3D this script sits on, and gives it the
# light's direction in the mesh's tangent frame every frame. Godot's importer is not used: the
# LUTs are 16-bit PNGs, read here at full precision. Copyright the btflut authors; MIT licence.
extends MeshInstance3D

## The export folder (absolute, res:// or user://).
@export_dir var export_folder: String = "res://material"
## A DirectionalLight3D (its direction) or any Node3D (its position: a point light).
@export var light: Node3D

var _material: ShaderMaterial


func _ready() -> void:
	_material = ShaderMaterial.new()
	_material.shader = load("res://btflut_relit.gdshader")
	var error := _load(export_folder)
	if error != "":
		push_error("btflut: " + error)
		return
	material_override = _material


func _process(_delta: float) -> void:
	if light == null or _material == null:
		return
	var towards: Vector3
	if light is DirectionalLight3D:
		towards = light.global_transform.basis.z  # a directional light shines along -z
	else:
		towards = (light.global_position - global_position).normalized()
	# A QuadMesh's u runs along +x, its v down along -y, its front faces +z: the tangent frame
	# (image right, image up, normal) is (x, y, z) of the mesh's basis.
	var b := global_transform.basis.orthonormalized()
	_material.set_shader_parameter("light_tangent", Vector3(towards.dot(b.x), towards.dot(b.y), towards.dot(b.z)))


# A PNG of 8 or 16 bits, grey, grey-alpha, RGB or RGBA, not interlaced: {width, height,
# channels, depth, samples: PackedInt32Array, rows top first}.
func _decode_png(path: String) -> Dictionary:
	var bytes := FileAccess.get_file_as_bytes(path)
	if bytes.is_empty():  # an exported game packs the file only under an export filter
		return {"error": path + ": cannot be read (exported games need the export filter material/*: docs/engines.md)"}
	if bytes.size() < 8 or bytes.slice(0, 8) != PackedByteArray([137, 80, 78, 71, 13, 10, 26, 10]):
		return {"error": path + ": not a PNG file"}
	var width := 0
	var height := 0
	var depth := 0
	var type := -1
	var data := PackedByteArray()
	var at := 8
	while at + 8 <= bytes.size():
		var length := bytes.decode_u32(at)  # little-endian: swapped below
		length = ((length & 0xff) << 24) | ((length & 0xff00) << 8) | ((length >> 8) & 0xff00) | ((length >> 24) & 0xff)
		var kind := bytes.slice(at + 4, at + 8).get_string_from_ascii()
		if at + 12 + length > bytes.size():
			return {"error": path + ": truncated " + kind + " chunk"}
		if kind == "IHDR":
			width = (bytes[at + 8] << 24) | (bytes[at + 9] << 16) | (bytes[at + 10] << 8) | bytes[at + 11]
			height = (bytes[at + 12] << 24) | (bytes[at + 13] << 16) | (bytes[at + 14] << 8) | bytes[at + 15]
			depth = bytes[at + 16]
			type = bytes[at + 17]
			if bytes[at + 20] != 0:
				return {"error": path + ": interlaced PNGs are not read"}
		elif kind == "IDAT":
			data.append_array(bytes.slice(at + 8, at + 8 + length))
		elif kind == "IEND":
			break
		at += 12 + length
	var channels: int = {0: 1, 2: 3, 4: 2, 6: 4}.get(type, 0)
	if channels == 0 or (depth != 8 and depth != 16):
		return {"error": path + ": PNG colour type %d, depth %d not read" % [type, depth]}
	var step := channels * depth / 8
	var stride := width * step
	var raw := data.decompress(height * (stride + 1), FileAccess.COMPRESSION_DEFLATE)
	if raw.size() < height * (stride + 1):
		return {"error": path + ": truncated image data"}
	var rows := PackedByteArray()
	rows.resize(height * stride)
	for y in height:
		var filter := raw[y * (stride + 1)]
		var line := y * (stride + 1) + 1
		var row := y * stride
		for i in stride:
			var a := rows[row + i - step] if i >= step else 0
			var b := rows[row - stride + i] if y > 0 else 0
			var c := rows[row - stride + i - step] if y > 0 and i >= step else 0
			var predictor := 0
			if filter == 1:
				predictor = a
			elif filter == 2:
				predictor = b
			elif filter == 3:
				predictor = (a + b) >> 1
			elif filter == 4:
				var p := a + b - c
				var pa := absi(p - a)
				var pb := absi(p - b)
				var pc := absi(p - c)
				predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
			elif filter != 0:
				return {"error": path + ": bad PNG filter %d" % filter}
			rows[row + i] = (raw[line + i] + predictor) & 255
	var samples := PackedInt32Array()
	samples.resize(width * height * channels)
	for i in samples.size():
		samples[i] = (rows[2 * i] << 8) | rows[2 * i + 1] if depth == 16 else rows[i]
	return {"width": width, "height": height, "channels": channels, "depth": depth, "samples": samples}


func _load(folder: String) -> String:
	var json = JSON.parse_string(FileAccess.get_file_as_string(folder.path_join("material.json")))
	if typeof(json) != TYPE_DICTIONARY or json.get("format") != "btflut-material":
		return folder.path_join("material.json") + ": not a btflut material"
	if int(json["version"]) > 2:
		return folder.path_join("material.json") + ": version %d is newer than this script reads (2)" % int(json["version"])
	# luts.png: a 3D texture of half floats (one channel, or RGB as RGBA), slice z = rows z*G .. z*G+G-1.
	var lut := _decode_png(folder.path_join(json["luts"]["file"]))
	if lut.has("error"):
		return lut["error"]
	var entries := int(json["luts"]["entries"])
	var g := int(json["luts"]["grid_size"])
	if lut["width"] != entries or lut["depth"] != 16 or lut["height"] % (g * g) != 0:
		return "luts.png: not the 16-bit %d x (%d x %d x blocks) image material.json describes" % [entries, g, g]
	var n := 1 if lut["channels"] == 1 else 4
	var slices: Array[Image] = []
	for z in lut["height"] / g:
		var halves := PackedByteArray()
		halves.resize(entries * g * n * 2)
		for t in entries * g:
			for c in n:
				var value := 1.0
				if c < lut["channels"]:
					value = lut["samples"][(z * entries * g + t) * lut["channels"] + c] / 65535.0
				halves.encode_half((t * n + c) * 2, value)
		slices.append(Image.create_from_data(entries, g, false, Image.FORMAT_RH if n == 1 else Image.FORMAT_RGBAH, halves))
	var luts := ImageTexture3D.new()
	luts.create(slices[0].get_format(), entries, g, slices.size(), false, slices)
	_material.set_shader_parameter("luts", luts)
	_material.set_shader_parameter("rgb_luts", json["colour"] == "rgb")
	_material.set_shader_parameter("grey_reference", int(json["reference"]["channels"]) == 1)
	_material.set_shader_parameter("input_code", float(json["lut_input_code"]))
	_material.set_shader_parameter("output_code", float(json["lut_output_code"]))
	if json["kind"] == "luts":
		_material.set_shader_parameter("kind", 0)
		var reference := Image.load_from_file(folder.path_join(json["reference"]["file"]))
		_material.set_shader_parameter("reference", ImageTexture.create_from_image(reference))
		return ""
	var p: Dictionary = json["predictor"]
	if p.get("network") != null:
		# A learned material's decoder specialised to it: a shader of its own that includes it.
		var shader := Shader.new()
		shader.code = _material.shader.code.replace("// btflut: network",
			'#include "%s"' % folder.path_join(p["network"]["godot"]))
		_material.shader = shader
	var files: Array = p["images"].duplicate()
	if p.get("albedo") != null:
		files.append(p["albedo"]["file"])
	var images: Array[Image] = []
	for file in files:
		var image := Image.load_from_file(folder.path_join(file))  # 8-bit PNGs: Godot's decoder keeps them
		image.convert(Image.FORMAT_RGBA8)
		image.generate_mipmaps()  # the prediction is linear in the planes
		images.append(image)
	var planes := Texture2DArray.new()
	planes.create_from_images(images)
	_material.set_shader_parameter("planes", planes)
	if p.get("weights") != null:
		var w: Dictionary = p["weights"]
		var bytes := FileAccess.get_file_as_bytes(folder.path_join(w["file"]))
		var s := int(w["grid_size"])
		if bytes.size() != s * s * int(w["layers"]) * 16:
			return "weights.bin: not the %dx%dx%d RGBA float32 layers material.json describes" % [s, s, int(w["layers"])]
		var layers: Array[Image] = []
		for k in int(w["layers"]):  # float32 little-endian: Godot's RGBAF as it is
			layers.append(Image.create_from_data(s, s, false, Image.FORMAT_RGBAF, bytes.slice(k * s * s * 16, (k + 1) * s * s * 16)))
		var weights := Texture2DArray.new()
		weights.create_from_images(layers)
		_material.set_shader_parameter("weights", weights)
	if p.get("labels") != null:
		var labels := Image.load_from_file(folder.path_join(p["labels"]["file"]))
		_material.set_shader_parameter("labels", ImageTexture.create_from_image(labels))
	var scale := PackedFloat32Array()
	var bias := PackedFloat32Array()
	scale.resize(32)
	bias.resize(32)
	for k in p.get("scale", []).size():
		scale[k] = p["scale"][k]
		bias[k] = p["bias"][k]
	_material.set_shader_parameter("kind", int(p["kind_index"]))  # BTFLUT_KIND_MODEL, _REFERENCES, _LEARNED
	_material.set_shader_parameter("basis", int(p.get("basis_index", 0)) if p["kind"] == "model" else 0)
	_material.set_shader_parameter("order", int(p.get("order", 0)))
	_material.set_shader_parameter("plane_count", int(p["planes"]))
	_material.set_shader_parameter("channels", int(p["channels"]))
	var albedo := 0
	if p.get("albedo") != null:
		albedo = 1 if p["albedo"]["use"] == "multiplies" else 2
	_material.set_shader_parameter("albedo", albedo)
	_material.set_shader_parameter("regions", int(p["regions"]))
	_material.set_shader_parameter("codes", float(p["codes"]))
	_material.set_shader_parameter("grey_output", int(p["output_channels"]) == 1)
	_material.set_shader_parameter("scale", scale)
	_material.set_shader_parameter("bias", bias)
	return ""
