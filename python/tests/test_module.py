"""The package's identity: version and build facts agree with the program's."""

import oceanref


def test_version_and_build_info(cli):
    assert oceanref.__version__ == "0.1.0"
    info = oceanref.build_info()
    version = cli("--version")
    assert version.startswith(info["version"])  # "oceanref 0.1.0 ..."
    assert "(commit " + info["commit"] + ")" in version  # the same build's commit
    assert "-ffp-contract=off" in info["flags"]
    assert info["math_library"] in version
    assert "flags: " + info["flags"] + "\n" in version
    assert set(oceanref.__all__) <= set(dir(oceanref))
