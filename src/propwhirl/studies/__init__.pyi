# The public names of propwhirl.studies for static tools (the documentation site's API page,
# type checkers): __init__.py imports them on first use (PEP 562), so that importing one study
# module loads no other.  Keep in step with _EXPORTS there (tests/test_doctests.py checks).
from propwhirl.studies.boundary import path_variant as path_variant
from propwhirl.studies.campaign import Campaign as Campaign
from propwhirl.studies.campaign_cases import Case as Case
from propwhirl.studies.flight_envelope import envelope as envelope
from propwhirl.studies.campaign import from_spec as from_spec
from propwhirl.studies.campaign import run_campaign as run_campaign
from propwhirl.studies.campaign_result import CampaignResult as CampaignResult
from propwhirl.studies.execution import map_analyses as map_analyses
from propwhirl.studies.gradients import minimum_mount_stiffness as minimum_mount_stiffness
from propwhirl.studies.gradients import openmdao_component as openmdao_component
from propwhirl.studies.parametric import blade_angle_mode_switch as blade_angle_mode_switch
from propwhirl.studies.parametric import nacelle_stiffness as nacelle_stiffness
from propwhirl.studies.sensitivity_check import verify_sensitivities as verify_sensitivities
from propwhirl.studies.sweeps import CriticalMap as CriticalMap
from propwhirl.studies.sweeps import critical_map as critical_map
from propwhirl.studies.sweeps import map2d as map2d
from propwhirl.studies.sweeps import sweep as sweep

__all__ = ["sweep", "map2d", "critical_map", "CriticalMap", "path_variant", "nacelle_stiffness",
           "blade_angle_mode_switch", "Case", "envelope", "Campaign", "from_spec",
           "run_campaign", "CampaignResult", "verify_sensitivities", "minimum_mount_stiffness",
           "openmdao_component", "map_analyses"]
